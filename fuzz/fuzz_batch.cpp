// fuzz_batch: the batch API (raykernel/batch.hpp) against the one-query path it promises to match bit for
// bit. The vectorized fast loop (AVX-512, AVX2 or portable, whichever the CPU runs) decides the queries it
// can certify and hands the rest to the full cascade; every lane must give `intersect_traced`'s answer, which
// fuzz_plane checks against CGAL.
//
// Input: a sequence of 97-byte records, each one query in the layout of raykernel/testkit/plane_fuzz_decoder.hpp
// (raw doubles or a hard query of one of the 13 kinds), up to 40 queries: enough to fill every SIMD lane and
// leave a scalar remainder. Checked:
//   - intersect_batch (pairwise, with `valid`): valid[i] is whether query i is valid input, and each valid
//     query's relation and the bits of t equal intersect_traced's; BatchStats equals the stages
//     intersect_traced reports, summed;
//   - intersect_batch without `valid`: throws invalid_input "query K: REASON" for the first invalid query K
//     (REASON is validate's), and otherwise gives the same answers;
//   - intersect_batch with one plane (the first query's) for every ray: the same against intersect_traced.
#include "fuzz_support.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_fuzz_decoder.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace {

using raykernel::fuzz::check;
namespace rt = raykernel::testkit;

constexpr std::size_t record_size = rt::raw_fuzz_input_size;  // 97
constexpr std::size_t max_queries = 40;

std::vector<rt::FuzzQuery> current;
raykernel::fuzz::StageCounts stats;

std::string describe_current() {
  std::string s = std::to_string(current.size()) + " queries (ox oy oz dx dy dz px py pz nx ny nz, hex floats):\n";
  for (std::size_t i = 0; i < current.size(); ++i) {
    s.append("  ").append(std::to_string(i)).append(": ");
    const rt::Query& q = current[i].query;
    for (const raykernel::Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal}) {
      for (double c : {v.x, v.y, v.z}) s += raykernel::fuzz::hex(c) + " ";
    }
    s.append("(").append(current[i].kind ? rt::to_string(*current[i].kind) : "raw").append(")\n");
  }
  return s;
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

// Structure-of-arrays copies of the rays and planes.
struct Arrays {
  std::vector<double> ox, oy, oz, dx, dy, dz, px, py, pz, nx, ny, nz;
  explicit Arrays(const std::vector<rt::FuzzQuery>& queries) {
    for (const rt::FuzzQuery& f : queries) {
      const raykernel::Ray& r = f.query.ray;
      const raykernel::Plane& p = f.query.plane;
      ox.push_back(r.origin.x), oy.push_back(r.origin.y), oz.push_back(r.origin.z);
      dx.push_back(r.direction.x), dy.push_back(r.direction.y), dz.push_back(r.direction.z);
      px.push_back(p.point.x), py.push_back(p.point.y), pz.push_back(p.point.z);
      nx.push_back(p.normal.x), ny.push_back(p.normal.y), nz.push_back(p.normal.z);
    }
  }
  raykernel::RayBatch rays() const { return {ox, oy, oz, dx, dy, dz}; }
  raykernel::PlaneBatch planes() const { return {px, py, pz, nx, ny, nz}; }
};

// What intersect_traced says about (ray, plane), or nothing for invalid input.
std::optional<raykernel::TracedIntersection> reference(const raykernel::Ray& ray, const raykernel::Plane& plane) {
  if (raykernel::validate(ray, plane)) return std::nullopt;
  return raykernel::intersect_traced(ray, plane);
}

void check_answers(const char* run, const std::vector<std::optional<raykernel::TracedIntersection>>& want,
                   const std::vector<raykernel::Relation>& relation, const std::vector<double>& t) {
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (!want[i]) continue;
    const raykernel::Intersection& w = want[i]->intersection;
    check(relation[i] == w.relation && bits(t[i]) == bits(w.t), [&] {
      return std::string(run) + ": query " + std::to_string(i) + " is " +
             std::string(raykernel::to_string(relation[i])) + " " + raykernel::fuzz::hex(t[i]) +
             ", intersect_traced says " + std::string(raykernel::to_string(w.relation)) + " " +
             raykernel::fuzz::hex(w.t);
    });
  }
}

void check_batch(const std::vector<rt::FuzzQuery>& queries) {
  const std::size_t n = queries.size();
  const Arrays arrays(queries);
  std::vector<std::optional<raykernel::TracedIntersection>> want(n);
  std::optional<std::size_t> first_invalid;
  raykernel::BatchStats want_stats;
  for (std::size_t i = 0; i < n; ++i) {
    want[i] = reference(queries[i].query.ray, queries[i].query.plane);
    if (!want[i]) {
      if (!first_invalid) first_invalid = i;
      stats.add_invalid();
      continue;
    }
    stats.add(*want[i]);
    ++want_stats.relation_stage[static_cast<std::size_t>(want[i]->relation_stage)];
    const raykernel::Relation r = want[i]->intersection.relation;
    if (r == raykernel::Relation::hit || r == raykernel::Relation::behind)
      ++want_stats.t_stage[static_cast<std::size_t>(want[i]->t_stage)];
  }

  // Pairwise, with `valid`: never throws.
  std::vector<raykernel::Relation> relation(n);
  std::vector<double> t(n);
  std::unique_ptr<bool[]> valid(new bool[n]);  // std::vector<bool> has no span
  raykernel::BatchStats got_stats;
  raykernel::intersect_batch(arrays.rays(), arrays.planes(), {relation, t, std::span<bool>(valid.get(), n)},
                             {.threads = 1, .stats = &got_stats});
  for (std::size_t i = 0; i < n; ++i) {
    check(valid[i] == want[i].has_value(),
          [&] { return "intersect_batch: valid[" + std::to_string(i) + "] is whether query i is valid input"; });
  }
  check_answers("intersect_batch (pairwise, with valid)", want, relation, t);
  check(got_stats.relation_stage == want_stats.relation_stage && got_stats.t_stage == want_stats.t_stage, [&] {
    auto list = [](const std::array<std::uint64_t, raykernel::stage_count>& a) {
      std::string s;
      for (std::uint64_t x : a) s.append(" ").append(std::to_string(x));
      return s;
    };
    return "BatchStats are intersect_traced's stages: batch relation" + list(got_stats.relation_stage) + ", t" +
           list(got_stats.t_stage) + "; intersect_traced relation" + list(want_stats.relation_stage) + ", t" +
           list(want_stats.t_stage);
  });

  // Pairwise, without `valid`: throws for the first invalid query.
  std::vector<raykernel::Relation> relation2(n);
  std::vector<double> t2(n);
  try {
    raykernel::intersect_batch(arrays.rays(), arrays.planes(), {relation2, t2}, {.threads = 1});
    check(!first_invalid, "intersect_batch without `valid` throws invalid_input for an invalid query");
    check_answers("intersect_batch (pairwise)", want, relation2, t2);
  } catch (const raykernel::invalid_input& e) {
    check(first_invalid.has_value(), [&] { return std::string("intersect_batch threw on valid input: ") + e.what(); });
    const rt::Query& q = queries[*first_invalid].query;
    const std::string expected =
        "query " + std::to_string(*first_invalid) + ": " + *raykernel::validate(q.ray, q.plane);
    check(expected == e.what(), [&] {
      return "intersect_batch names the first invalid query: expected '" + expected + "', got '" + e.what() + "'";
    });
  }

  // One plane (the first query's) for every ray.
  const raykernel::Plane plane = queries[0].query.plane;
  std::vector<std::optional<raykernel::TracedIntersection>> want_broadcast(n);
  for (std::size_t i = 0; i < n; ++i) want_broadcast[i] = reference(queries[i].query.ray, plane);
  std::vector<raykernel::Relation> relation3(n);
  std::vector<double> t3(n);
  std::unique_ptr<bool[]> valid3(new bool[n]);
  raykernel::intersect_batch(arrays.rays(), plane, {relation3, t3, std::span<bool>(valid3.get(), n)}, {.threads = 1});
  for (std::size_t i = 0; i < n; ++i) {
    check(valid3[i] == want_broadcast[i].has_value(), [&] {
      return "intersect_batch (one plane): valid[" + std::to_string(i) + "] is whether (ray i, plane) is valid input";
    });
  }
  check_answers("intersect_batch (one plane)", want_broadcast, relation3, t3);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("batch");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit([] {
      std::fputs(raykernel::fuzz::format_stage_table("batch (every query of every batch)", {{"all", stats}}).c_str(),
                 stderr);
    });
    return true;
  }();
  (void)initialized;
  const std::span<const std::uint8_t> bytes(data, size);
  current.clear();
  for (std::size_t offset = 0; offset < size && current.size() < max_queries; offset += record_size) {
    current.push_back(rt::decode_fuzz_query(bytes.subspan(offset, std::min(record_size, size - offset))));
  }
  if (current.empty()) current.push_back(rt::decode_fuzz_query({}));
  check_batch(current);
  return 0;
}
