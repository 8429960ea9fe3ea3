// The batch API (raykernel/batch.hpp): the fast path of the cascade as one vectorized loop, then the
// queries it could not certify one by one through the rest of the cascade.
//
// The loop (plane/fast_loop.hpp) is compiled three times — for AVX-512, for AVX2 with FMA, and portably —
// in fast_loop_*.cpp, and the widest the CPU supports is chosen on first use. Each lane computes exactly the
// operations the scalar path computes for that query, so the answers are the same bits. Each worker thread
// runs in the default floating-point environment (fp_environment.hpp) and restores its own on exit.
#include <raykernel/batch.hpp>
#include <raykernel/parallel.hpp>

#include "plane/fast_loop.hpp"
#include "core/fp_requirements.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "core/fp_environment.hpp"
#include "core/validation.hpp"

#include <algorithm>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace raykernel {
namespace {

using batch_kernel::certified_by_fast_path;
using batch_kernel::LoopAnswer;
using batch_kernel::PlaneArrays;
using batch_kernel::RayArrays;
using batch_kernel::relation_by_compensated;

// The instruction set of the fast loops, chosen once: AVX-512, AVX2 with FMA, or portable.
struct FastLoops {
  batch_kernel::LoopFunction pairwise, broadcast, pairwise_relation, broadcast_relation;

  [[nodiscard]] batch_kernel::LoopFunction get(bool broadcast_plane, LoopAnswer what) const noexcept {
    if (what == LoopAnswer::relation) return broadcast_plane ? broadcast_relation : pairwise_relation;
    return broadcast_plane ? broadcast : pairwise;
  }
};
#define RAYKERNEL_FAST_LOOPS(isa)                                                                             \
  FastLoops {                                                                                                 \
    batch_kernel::isa::pairwise, batch_kernel::isa::broadcast, batch_kernel::isa::pairwise_relation,          \
        batch_kernel::isa::broadcast_relation                                                                 \
  }
const FastLoops& fast_loops() {
  static const FastLoops loops = [] {
#if defined(RAYKERNEL_BATCH_AVX512) || defined(RAYKERNEL_BATCH_AVX2)
    __builtin_cpu_init();
#endif
#if defined(RAYKERNEL_BATCH_AVX512)
    if (__builtin_cpu_supports("x86-64-v4")) return RAYKERNEL_FAST_LOOPS(avx512);
#endif
#if defined(RAYKERNEL_BATCH_AVX2)
    if (__builtin_cpu_supports("x86-64-v3")) return RAYKERNEL_FAST_LOOPS(avx2);
#endif
    return RAYKERNEL_FAST_LOOPS(portable);
  }();
  return loops;
}
#undef RAYKERNEL_FAST_LOOPS

// The first invalid query of a range (lowest index), to be thrown after the threads join.
struct FirstError {
  std::size_t index = std::numeric_limits<std::size_t>::max();
  std::string reason;
};

struct Job {
  RayArrays rays;
  PlaneArrays planes;
  bool broadcast_plane;
  LoopAnswer what;
  std::span<Relation> relation;
  std::span<double> t;  // empty for relation jobs
  std::span<bool> valid;
};

// One query the fast loop left open: validation, then the cascade (with its stages, for the statistics).
// Returns false for invalid input, with the reason.
bool answer_rest(const Job& job, std::size_t i, BatchStats& stats, std::string& reason) {
  const std::size_t k = job.broadcast_plane ? 0 : i;
  const RayArrays& r = job.rays;
  const PlaneArrays& p = job.planes;
  const Ray ray{{r.ox[i], r.oy[i], r.oz[i]}, {r.dx[i], r.dy[i], r.dz[i]}};
  const Plane plane{{p.px[k], p.py[k], p.pz[k]}, {p.nx[k], p.ny[k], p.nz[k]}};
  if (!(detail::is_valid(ray) & detail::is_valid(plane))) {
    reason = *validate(ray, plane);
    return false;
  }
  detail::RayPlaneCascade query(ray, plane);
  if (job.what == LoopAnswer::relation) {
    const detail::CertifiedSigns signs = detail::certified_signs(query);
    job.relation[i] = detail::relation_from_signs(static_cast<int>(signs.num), static_cast<int>(signs.den));
    ++stats.relation_stage[static_cast<std::size_t>(signs.stage)];
    return true;
  }
  const TracedIntersection a = detail::intersect_cascade(query);
  job.relation[i] = a.intersection.relation;
  job.t[i] = a.intersection.t;
  ++stats.relation_stage[static_cast<std::size_t>(a.relation_stage)];
  if (a.intersection.relation == Relation::hit || a.intersection.relation == Relation::behind)
    ++stats.t_stage[static_cast<std::size_t>(a.t_stage)];
  return true;
}

// Runs [begin, end) of a job: the vectorized loop, then the rest through the cascade.
void run_range(const Job& job, std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
  const std::size_t n = end - begin;
  std::vector<std::uint8_t> outcome(n, 0);
  const batch_kernel::LoopFunction loop = fast_loops().get(job.broadcast_plane, job.what);
  const bool with_t = job.what == LoopAnswer::intersection;
  // Chunks keep the outcome buffer and the answers in cache between the two passes.
  constexpr std::size_t chunk = 4096;
  for (std::size_t c = begin; c < end; c += chunk) {
    const std::size_t c_end = std::min(end, c + chunk);
    std::uint8_t* out_flags = outcome.data() + (c - begin);
    loop(job.rays, job.planes, c, c_end, job.relation.data(), with_t ? job.t.data() : nullptr, out_flags - c);
    for (std::size_t i = c; i < c_end; ++i) {
      // Eight queries certified by the filter (and, for t, the first compensated level) at once.
      constexpr std::uint64_t eight_certified = 0x0101010101010101ULL * certified_by_fast_path;
      if (i + 8 <= c_end && (i - c) % 8 == 0) {
        std::uint64_t word;
        std::memcpy(&word, out_flags + (i - c), sizeof word);
        if (word == eight_certified) {
          stats.relation_stage[static_cast<std::size_t>(Stage::filter)] += 8;
          if (with_t) stats.t_stage[static_cast<std::size_t>(Stage::compensated)] += 8;
          if (!job.valid.empty()) std::fill_n(job.valid.begin() + static_cast<std::ptrdiff_t>(i), 8, true);
          i += 7;
          continue;
        }
      }
      const std::uint8_t flags = out_flags[i - c];
      if (!job.valid.empty()) job.valid[i] = true;
      if (flags & certified_by_fast_path) {
        ++stats.relation_stage[static_cast<std::size_t>((flags & relation_by_compensated) ? Stage::compensated : Stage::filter)];
        if (with_t) ++stats.t_stage[static_cast<std::size_t>(Stage::compensated)];
        continue;
      }
      std::string reason;
      if (answer_rest(job, i, stats, reason)) continue;
      job.relation[i] = Relation::in_plane;
      if (with_t) job.t[i] = std::numeric_limits<double>::quiet_NaN();
      if (!job.valid.empty()) {
        job.valid[i] = false;
      } else if (i < error.index) {
        error = {i, std::move(reason)};
        return;  // the caller throws; the rest of this range is not needed
      }
    }
  }
}

// The parts a batch of n is split into: one per thread (thread_count), each at least 2^14 queries — below
// that, a thread costs more than it gains.
std::size_t part_count(std::size_t n, unsigned requested) {
  constexpr std::size_t per_part_minimum = std::size_t{1} << 14;
  return std::clamp<std::size_t>(n / per_part_minimum, 1, thread_count(requested));
}

// Splits [0, n) into parts, runs `work(begin, end, stats, error)` on each (over threads, run_parts) in the
// default floating-point environment, merges, and throws the lowest-index error as "<what> N: reason".
template <class Work>
void run_parallel(std::size_t n, const BatchOptions& options, const char* what, Work work) {
  const std::size_t parts = part_count(n, options.threads);
  std::vector<BatchStats> stats(parts);
  std::vector<FirstError> errors(parts);
  run_parts(parts, static_cast<unsigned>(parts), [&](std::size_t k) {
    const std::size_t begin = n * k / parts, end = n * (k + 1) / parts;
    detail::in_default_fp_environment([&] { work(begin, end, stats[k], errors[k]); });
  });
  const auto first = std::min_element(errors.begin(), errors.end(),
                                      [](const FirstError& a, const FirstError& b) { return a.index < b.index; });
  if (first->index != std::numeric_limits<std::size_t>::max())
    throw invalid_input(std::string(what) + " " + std::to_string(first->index) + ": " + first->reason);
  if (options.stats != nullptr) {
    for (const BatchStats& s : stats)
      for (std::size_t k = 0; k < stage_count; ++k) {
        options.stats->relation_stage[k] += s.relation_stage[k];
        options.stats->t_stage[k] += s.t_stage[k];
      }
  }
}

void check_sizes(const char* function, const RayBatch& rays, std::size_t planes, std::size_t relation,
                 std::size_t t, std::size_t valid, bool with_t) {
  const std::size_t n = rays.size();
  const bool ok = rays.oy.size() == n && rays.oz.size() == n && rays.dx.size() == n && rays.dy.size() == n &&
                  rays.dz.size() == n && (planes == 1 || planes == n) && relation == n && (!with_t || t == n) &&
                  (valid == 0 || valid == n);
  if (!ok) throw std::invalid_argument(std::string(function) + ": the spans of rays, planes and answers differ in size");
}

std::size_t checked_size(const char* function, const PlaneBatch& planes) {
  const std::size_t n = planes.size();
  if (planes.py.size() != n || planes.pz.size() != n || planes.nx.size() != n || planes.ny.size() != n ||
      planes.nz.size() != n)
    throw std::invalid_argument(std::string(function) + ": the spans of rays, planes and answers differ in size");
  return n;
}

RayArrays arrays_of(const RayBatch& r) { return {r.ox.data(), r.oy.data(), r.oz.data(), r.dx.data(), r.dy.data(), r.dz.data()}; }
PlaneArrays arrays_of(const PlaneBatch& p) { return {p.px.data(), p.py.data(), p.pz.data(), p.nx.data(), p.ny.data(), p.nz.data()}; }
PlaneArrays arrays_of(const Plane& p) {
  return {&p.point.x, &p.point.y, &p.point.z, &p.normal.x, &p.normal.y, &p.normal.z};
}

void run_job(const Job& job, std::size_t n, const BatchOptions& options) {
  run_parallel(n, options, "query", [&job](std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
    run_range(job, begin, end, stats, error);
  });
}

}  // namespace

void intersect_batch(const RayBatch& rays, const PlaneBatch& planes, IntersectionBatch out, BatchOptions options) {
  check_sizes("intersect_batch", rays, checked_size("intersect_batch", planes), out.relation.size(), out.t.size(),
              out.valid.size(), true);
  run_job({arrays_of(rays), arrays_of(planes), false, LoopAnswer::intersection, out.relation, out.t, out.valid},
          rays.size(), options);
}

void intersect_batch(const RayBatch& rays, const Plane& plane, IntersectionBatch out, BatchOptions options) {
  check_sizes("intersect_batch", rays, 1, out.relation.size(), out.t.size(), out.valid.size(), true);
  run_job({arrays_of(rays), arrays_of(plane), true, LoopAnswer::intersection, out.relation, out.t, out.valid},
          rays.size(), options);
}

void relation_batch(const RayBatch& rays, const PlaneBatch& planes, RelationBatch out, BatchOptions options) {
  check_sizes("relation_batch", rays, checked_size("relation_batch", planes), out.relation.size(), 0,
              out.valid.size(), false);
  run_job({arrays_of(rays), arrays_of(planes), false, LoopAnswer::relation, out.relation, {}, out.valid},
          rays.size(), options);
}

void relation_batch(const RayBatch& rays, const Plane& plane, RelationBatch out, BatchOptions options) {
  check_sizes("relation_batch", rays, 1, out.relation.size(), 0, out.valid.size(), false);
  run_job({arrays_of(rays), arrays_of(plane), true, LoopAnswer::relation, out.relation, {}, out.valid}, rays.size(),
          options);
}

void nearest_hit_batch(const RayBatch& rays, const PlaneSet& planes, std::span<std::optional<NearestHit>> out,
                       BatchOptions options) {
  const std::size_t n = rays.size();
  if (rays.oy.size() != n || rays.oz.size() != n || rays.dx.size() != n || rays.dy.size() != n ||
      rays.dz.size() != n || out.size() != n)
    throw std::invalid_argument("nearest_hit_batch: the spans of rays and answers differ in size");
  run_parallel(n, options, "ray", [&](std::size_t begin, std::size_t end, BatchStats& stats, FirstError& error) {
    for (std::size_t i = begin; i < end; ++i) {
      const Ray ray{{rays.ox[i], rays.oy[i], rays.oz[i]}, {rays.dx[i], rays.dy[i], rays.dz[i]}};
      if (!detail::is_valid(ray)) {
        if (i < error.index) error = {i, *validate(ray)};
        return;
      }
      const TracedNearestHit traced = nearest_hit_traced(ray, planes);
      out[i] = traced.hit;
      ++stats.relation_stage[static_cast<std::size_t>(traced.relation_stage)];
      if (traced.hit) ++stats.t_stage[static_cast<std::size_t>(traced.t_stage)];
    }
  });
}

void nearest_hit_batch(const RayBatch& rays, std::span<const Plane> planes, std::span<std::optional<NearestHit>> out,
                       BatchOptions options) {
  nearest_hit_batch(rays, PlaneSet(planes), out, options);
}

}  // namespace raykernel
