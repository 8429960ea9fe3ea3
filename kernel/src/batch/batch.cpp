// The batch API (raykernel/batch.hpp): the fast path of the cascade as one vectorized loop, then the
// queries it could not certify one by one through the full cascade.
//
// The loop (batch/fast_loop.hpp) is compiled three times — for AVX-512, for AVX2 with FMA, and portably —
// in fast_loop_*.cpp, and the widest the CPU supports is chosen on first use. Each lane computes exactly the
// operations the scalar path computes for that query, so the answers are the same bits.
#include <raykernel/batch.hpp>

#include "batch/fast_loop.hpp"
#include "certified/fp_requirements.hpp"
#include "entry_checks.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>


namespace raykernel {
namespace {

using batch_kernel::PlaneArrays;
using batch_kernel::RayArrays;
using batch_kernel::certified_by_fast_path;
using batch_kernel::relation_by_compensated;

// The instruction set of the fast loop, chosen once: AVX-512, AVX2 with FMA, or portable.
struct FastLoops {
  batch_kernel::LoopFunction pairwise, broadcast;
};
const FastLoops& fast_loops() {
  static const FastLoops loops = [] {
#if defined(RAYKERNEL_BATCH_AVX512) || defined(RAYKERNEL_BATCH_AVX2)
    __builtin_cpu_init();
#endif
#if defined(RAYKERNEL_BATCH_AVX512)
    if (__builtin_cpu_supports("x86-64-v4")) return FastLoops{batch_kernel::avx512::pairwise, batch_kernel::avx512::broadcast};
#endif
#if defined(RAYKERNEL_BATCH_AVX2)
    if (__builtin_cpu_supports("x86-64-v3")) return FastLoops{batch_kernel::avx2::pairwise, batch_kernel::avx2::broadcast};
#endif
    return FastLoops{batch_kernel::portable::pairwise, batch_kernel::portable::broadcast};
  }();
  return loops;
}

// The first invalid query of a range (lowest index), to be thrown after the threads join.
struct FirstError {
  std::size_t index = std::numeric_limits<std::size_t>::max();
  std::string reason;
};

struct Job {
  RayArrays rays;
  PlaneArrays planes;
  bool broadcast_plane;
  IntersectionBatch out;
  bool fast_path_allowed;  // the floating-point environment is the one the fast path assumes
};

// Runs [begin, end) of a job: the vectorized loop, then the rest through intersect_traced.
void run_range(const Job& job, std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
  const std::size_t n = end - begin;
  std::vector<std::uint8_t> outcome(n, 0);
  Relation* relation = job.out.relation.data();
  double* t = job.out.t.data();
  // Chunks keep the outcome buffer and the answers in cache between the two passes.
  constexpr std::size_t chunk = 4096;
  for (std::size_t c = begin; c < end; c += chunk) {
    const std::size_t c_end = std::min(end, c + chunk);
    std::uint8_t* out_flags = outcome.data() + (c - begin);
    if (job.fast_path_allowed) {
      const FastLoops& loops = fast_loops();
      (job.broadcast_plane ? loops.broadcast : loops.pairwise)(job.rays, job.planes, c, c_end, relation, t,
                                                                out_flags - c);
    }
    for (std::size_t i = c; i < c_end; ++i) {
      // Eight queries certified by the filter and the first compensated level (the common case) at once.
      constexpr std::uint64_t eight_certified = 0x0101010101010101ULL * certified_by_fast_path;
      if (i + 8 <= c_end && (i - c) % 8 == 0) {
        std::uint64_t word;
        std::memcpy(&word, out_flags + (i - c), sizeof word);
        if (word == eight_certified) {
          stats.relation_stage[static_cast<std::size_t>(Stage::filter)] += 8;
          stats.t_stage[static_cast<std::size_t>(Stage::compensated)] += 8;
          if (!job.out.valid.empty()) std::fill_n(job.out.valid.begin() + static_cast<std::ptrdiff_t>(i), 8, true);
          i += 7;
          continue;
        }
      }
      const std::uint8_t flags = out_flags[i - c];
      if (!job.out.valid.empty()) job.out.valid[i] = true;
      if (flags & certified_by_fast_path) {
        ++stats.relation_stage[static_cast<std::size_t>((flags & relation_by_compensated) ? Stage::compensated : Stage::filter)];
        ++stats.t_stage[static_cast<std::size_t>(Stage::compensated)];
        continue;
      }
      const std::size_t k = job.broadcast_plane ? 0 : i;
      const RayArrays& r = job.rays;
      const PlaneArrays& p = job.planes;
      const Ray ray{{r.ox[i], r.oy[i], r.oz[i]}, {r.dx[i], r.dy[i], r.dz[i]}};
      const Plane plane{{p.px[k], p.py[k], p.pz[k]}, {p.nx[k], p.ny[k], p.nz[k]}};
      try {
        const TracedIntersection a = intersect_traced(ray, plane);
        relation[i] = a.intersection.relation;
        t[i] = a.intersection.t;
        ++stats.relation_stage[static_cast<std::size_t>(a.relation_stage)];
        if (a.intersection.relation == Relation::hit || a.intersection.relation == Relation::behind)
          ++stats.t_stage[static_cast<std::size_t>(a.t_stage)];
      } catch (const invalid_input& e) {
        relation[i] = Relation::in_plane;
        t[i] = std::numeric_limits<double>::quiet_NaN();
        if (!job.out.valid.empty()) {
          job.out.valid[i] = false;
        } else if (i < error.index) {
          error = {i, e.what()};
          return;  // the caller throws; the rest of this range is not needed
        }
      }
    }
  }
}

unsigned thread_count(std::size_t n, unsigned requested) {
  constexpr std::size_t per_thread_minimum = std::size_t{1} << 14;  // below this, threads cost more than they gain
  unsigned hardware = requested != 0 ? requested : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::clamp<std::size_t>(n / per_thread_minimum, 1, hardware));
}

// Splits [0, n) over threads, runs `work(begin, end, stats, error)` on each part, merges, and throws the
// lowest-index error.
template <class Work>
void run_parallel(std::size_t n, const BatchOptions& options, Work work) {
  const unsigned threads = thread_count(n, options.threads);
  std::vector<BatchStats> stats(threads);
  std::vector<FirstError> errors(threads);
  std::vector<std::exception_ptr> failures(threads);
  auto part = [&](unsigned k) {
    const std::size_t begin = n * k / threads, end = n * (k + 1) / threads;
    try {
      work(begin, end, stats[k], errors[k]);
    } catch (...) {
      failures[k] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  for (unsigned k = 1; k < threads; ++k) pool.emplace_back(part, k);
  part(0);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& f : failures)
    if (f) std::rethrow_exception(f);
  const auto first = std::min_element(errors.begin(), errors.end(),
                                      [](const FirstError& a, const FirstError& b) { return a.index < b.index; });
  if (first->index != std::numeric_limits<std::size_t>::max())
    throw invalid_input("query " + std::to_string(first->index) + ": " + first->reason);
  if (options.stats != nullptr) {
    for (const BatchStats& s : stats)
      for (int k = 0; k < stage_count; ++k) {
        options.stats->relation_stage[static_cast<std::size_t>(k)] += s.relation_stage[static_cast<std::size_t>(k)];
        options.stats->t_stage[static_cast<std::size_t>(k)] += s.t_stage[static_cast<std::size_t>(k)];
      }
  }
}

void check_sizes(const RayBatch& rays, std::size_t planes, const IntersectionBatch& out) {
  const std::size_t n = rays.size();
  const bool ok = rays.oy.size() == n && rays.oz.size() == n && rays.dx.size() == n && rays.dy.size() == n &&
                  rays.dz.size() == n && (planes == 1 || planes == n) && out.relation.size() == n &&
                  out.t.size() == n && (out.valid.empty() || out.valid.size() == n);
  if (!ok) throw std::invalid_argument("intersect_batch: the spans of rays, planes and answers differ in size");
}

void run_job(const Job& job, std::size_t n, const BatchOptions& options) {
  run_parallel(n, options, [&job](std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
    run_range(job, begin, end, stats, error);
  });
}

}  // namespace

void intersect_batch(const RayBatch& rays, const PlaneBatch& planes, IntersectionBatch out, BatchOptions options) {
  const std::size_t n = planes.size();
  if (planes.py.size() != n || planes.pz.size() != n || planes.nx.size() != n || planes.ny.size() != n ||
      planes.nz.size() != n || n != rays.size())
    throw std::invalid_argument("intersect_batch: the spans of rays, planes and answers differ in size");
  check_sizes(rays, n, out);
  const Job job{{rays.ox.data(), rays.oy.data(), rays.oz.data(), rays.dx.data(), rays.dy.data(), rays.dz.data()},
                {planes.px.data(), planes.py.data(), planes.pz.data(), planes.nx.data(), planes.ny.data(), planes.nz.data()},
                false,
                out,
                detail::default_floating_point_environment()};
  run_job(job, n, options);
}

void intersect_batch(const RayBatch& rays, const Plane& plane, IntersectionBatch out, BatchOptions options) {
  check_sizes(rays, 1, out);
  const Job job{{rays.ox.data(), rays.oy.data(), rays.oz.data(), rays.dx.data(), rays.dy.data(), rays.dz.data()},
                {&plane.point.x, &plane.point.y, &plane.point.z, &plane.normal.x, &plane.normal.y, &plane.normal.z},
                true,
                out,
                detail::default_floating_point_environment()};
  run_job(job, rays.size(), options);
}

void nearest_hit_batch(const RayBatch& rays, std::span<const Plane> planes, std::span<std::optional<NearestHit>> out,
                       BatchOptions options) {
  const std::size_t n = rays.size();
  if (rays.oy.size() != n || rays.oz.size() != n || rays.dx.size() != n || rays.dy.size() != n ||
      rays.dz.size() != n || out.size() != n)
    throw std::invalid_argument("nearest_hit_batch: the spans of rays and answers differ in size");
  for (std::size_t k = 0; k < planes.size(); ++k)
    if (std::optional<std::string> reason = validate_plane(planes[k]))
      throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
  run_parallel(n, options, [&](std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
    for (std::size_t i = begin; i < end; ++i) {
      const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
      if (std::optional<std::string> reason = validate_ray(ray)) {
        if (i < error.index) error = {i, *reason};
        return;
      }
      const TracedNearestHit traced = nearest_hit_traced(ray, planes);
      out[i] = traced.hit;
      ++stats.relation_stage[static_cast<std::size_t>(traced.relation_stage)];
      if (traced.hit) ++stats.t_stage[static_cast<std::size_t>(traced.t_stage)];
    }
  });
}

}  // namespace raykernel
