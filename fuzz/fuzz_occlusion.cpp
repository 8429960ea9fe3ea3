// fuzz_occlusion: rays with an interval and segments against a small mesh (docs/contract.md §8), answered by
// raykernel's certified queries (`nearest_hit` with an interval, `occluded` for rays and segments,
// `segment_meets`) and checked against the exact path (`nearest_hit_exact`, `occluded_exact`,
// `segment_meets_exact`: every triangle in rationals).
//
// Input (structure-aware, so that vertices, edges, exact bounds and endpoints on faces are the common case):
//   byte 0        the mesh (mesh_words.hpp, words_mesh: octahedron or subdivided cube, scale, extra triangles),
//                 bits 4–5 the rule (owned twice as often)
//   then records of 8-byte little-endian words, each read as a double by `choose` (mesh_words.hpp):
//   the extra triangles (9 words each), the ray (6 words), the interval (2 words: each the raw bits, 0, +inf, or the
//   rounded t of the ray against a triangle, an ulp either side), the segment (6 words).
//
// Checked for every input:
//   - validity from the bits alone: an invalid ray, interval or segment (non-finite, zero direction, NaN or
//     negative bounds, t_min = +inf, t_min > t_max, p = q) throws invalid_input, a valid one does not;
//   - valid input: nearest_hit (interval) == nearest_hit_exact (triangle and t), occluded(ray) ==
//     occluded_exact(ray) == nearest_hit_exact found something, all_hits == all_hits_exact (triangles in order, t,
//     the crossing count); for the segment, segment_meets == segment_meets_exact
//     for every triangle, occluded(p, q) == their union == occluded_exact(p, q) == occluded(q, p).
#include "fuzz_support.hpp"
#include "mesh_words.hpp"

#include <raykernel/occlusion.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

namespace {

using raykernel::Mesh;
using raykernel::Ray;
using raykernel::RayInterval;
using raykernel::TriangleRule;
using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::finite_by_bits;
using raykernel::fuzz::hex;
using raykernel::fuzz::point;
using raykernel::fuzz::Reader;
using raykernel::fuzz::zero_by_bits;

constexpr double inf = std::numeric_limits<double>::infinity();

// A bound: the raw bits, 0, +inf, or near the rounded t of the ray against a triangle.
double bound(std::uint64_t w, const Ray& ray, const Mesh& mesh) {
  switch (w >> 62) {
    case 0: return std::bit_cast<double>(w << 2);
    case 1: return (w & 1) ? 0.0 : inf;
    default: {
      if (!raykernel::fuzz::finite_vector_by_bits(ray.origin) || !raykernel::fuzz::finite_vector_by_bits(ray.direction) ||
          raykernel::fuzz::zero_vector_by_bits(ray.direction))
        return 0;
      const double t = raykernel::intersect(ray, mesh.triangle((w >> 2) % mesh.triangles.size())).t;
      if (std::isnan(t)) return 1;
      const int step = static_cast<int>((w & 3) % 3) - 1;  // the low two bits: 0, 1, 2 (3 as 0)
      return step == 0 ? t : std::nextafter(t, step > 0 ? inf : -inf);
    }
  }
}

// docs/contract.md §8's valid interval, from the bits.
bool interval_valid_by_bits(const RayInterval& i) {
  const std::uint64_t lo = bits(i.t_min), hi = bits(i.t_max);
  const bool lo_nonneg = (lo >> 63) == 0 || zero_by_bits(i.t_min), hi_nonneg = (hi >> 63) == 0 || zero_by_bits(i.t_max);
  const bool hi_not_nan = finite_by_bits(i.t_max) || (hi << 12) == 0;
  const std::uint64_t lo_m = lo & ~(std::uint64_t{1} << 63), hi_m = hi & ~(std::uint64_t{1} << 63);
  return finite_by_bits(i.t_min) && lo_nonneg && hi_not_nan && hi_nonneg && lo_m <= hi_m;
}

template <class F>
bool throws_invalid(F&& f) {
  try {
    (void)f();
  } catch (const raykernel::invalid_input&) {
    return true;
  }
  return false;
}

std::string text(const Vec3& v) { return hex(v.x) + " " + hex(v.y) + " " + hex(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  raykernel::fuzz::set_harness_name("occlusion");
  if (size == 0) return 0;
  const std::uint8_t head = data[0];
  const TriangleRule rule = ((head >> 4) & 3) == 3 ? TriangleRule::closed : TriangleRule::owned;
  Reader r{data, size, 1};
  raykernel::fuzz::WordsMesh built = raykernel::fuzz::words_mesh(head, r);
  const Mesh& mesh = built.mesh;
  const int scale = built.scale;
  const raykernel::PreparedMesh prepared(mesh);

  const Vec3 o = point(r, mesh, scale), d = point(r, mesh, scale);
  const Ray ray{o, d};
  const double b1 = bound(r.word(), ray, mesh), b2 = bound(r.word(), ray, mesh);
  const RayInterval interval{b1, b2};
  const Vec3 p = point(r, mesh, scale), q = point(r, mesh, scale);
  raykernel::fuzz::set_input_describer([&] {
    return "ray " + text(o) + " + t·" + text(d) + " in [" + hex(b1) + ", " + hex(b2) + "], segment " + text(p) +
           " → " + text(q) + ", rule " + std::string(raykernel::to_string(rule)) + ", " +
           std::to_string(mesh.triangles.size()) + " triangles";
  });

  const bool ray_valid = raykernel::fuzz::finite_vector_by_bits(o) && raykernel::fuzz::finite_vector_by_bits(d) &&
                         !raykernel::fuzz::zero_vector_by_bits(d);
  if (!ray_valid || !interval_valid_by_bits(interval)) {
    check(throws_invalid([&] { return raykernel::occluded(ray, interval, prepared, rule); }),
          "an invalid ray or interval must throw invalid_input (occluded)");
    check(throws_invalid([&] { return raykernel::nearest_hit(ray, interval, prepared, rule); }),
          "an invalid ray or interval must throw invalid_input (nearest_hit)");
  } else {
    const auto fast = raykernel::nearest_hit(ray, interval, prepared, rule);
    const auto exact = raykernel::nearest_hit_exact(ray, interval, mesh, rule);
    check(fast.has_value() == exact.has_value(), "nearest_hit with an interval: hit or miss as the exact path");
    if (fast) {
      check(fast->triangle == exact->triangle, "nearest_hit with an interval: the exact path's triangle");
      check(bits(fast->intersection.t) == bits(exact->intersection.t), "nearest_hit with an interval: the exact t");
    }
    check(raykernel::occluded(ray, interval, prepared, rule) == exact.has_value(), "occluded(ray) == the exact path");
    const raykernel::MeshHits all = raykernel::all_hits(ray, interval, prepared, rule);
    const raykernel::MeshHits all_exact = raykernel::all_hits_exact(ray, interval, mesh, rule);
    check(all.hits.size() == all_exact.hits.size() && all.crossings == all_exact.crossings,
          "all_hits: as many hits and the same crossing count as the exact path");
    for (std::size_t k = 0; k < all.hits.size(); ++k)
      check(all.hits[k].triangle == all_exact.hits[k].triangle &&
                bits(all.hits[k].intersection.t) == bits(all_exact.hits[k].intersection.t),
            [&] { return "all_hits: hit " + std::to_string(k) + " is the exact path's"; });
  }

  const bool same = [&] {
    auto eq = [](double x, double y) { return bits(x) == bits(y) || (zero_by_bits(x) && zero_by_bits(y)); };
    return eq(p.x, q.x) && eq(p.y, q.y) && eq(p.z, q.z);
  }();
  if (!raykernel::fuzz::finite_vector_by_bits(p) || !raykernel::fuzz::finite_vector_by_bits(q) || same) {
    check(throws_invalid([&] { return raykernel::occluded(p, q, prepared, rule); }),
          "an invalid segment must throw invalid_input");
    return 0;
  }
  bool any = false;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const bool meets = raykernel::segment_meets(p, q, mesh.triangle(k), rule);
    check(meets == raykernel::segment_meets_exact(p, q, mesh.triangle(k), rule),
          [&] { return "segment_meets == segment_meets_exact, triangle " + std::to_string(k); });
    any = any || meets;
  }
  check(raykernel::occluded(p, q, prepared, rule) == any, "occluded(p, q) == some triangle meets the segment");
  check(raykernel::occluded(q, p, prepared, rule) == any, "occluded(q, p) == occluded(p, q)");
  check(raykernel::occluded_exact(p, q, mesh, rule) == any, "occluded_exact(p, q) == the union");
  return 0;
}
