// fuzz_occlusion: rays with an interval and segments against a small mesh (docs/contract.md §8), answered by
// raykernel's certified queries (`nearest_hit` with an interval, `occluded` for rays and segments,
// `segment_meets`) and checked against the exact path (`nearest_hit_exact`, `occluded_exact`,
// `segment_meets_exact`: every triangle in rationals).
//
// Input (structure-aware, so that vertices, edges, exact bounds and endpoints on faces are the common case):
//   byte 0        the mesh: bit 0 octahedron or subdivided cube (testkit, closed), bits 1–3 its scale 2^(4·(b − 4)),
//                 bits 4–5 the rule (owned twice as often), bits 6–7 how many extra triangles (0–3)
//   then records of 8-byte little-endian words, each read as a double by `choose`:
//                 tag < 0x40: the raw bits of the rest; 0x40..0x7F: a vertex coordinate of the mesh; 0x80..0xBF:
//                 a multiple of a quarter of the scale in [−2, 2]; 0xC0..0xFF: a small integer times the scale
//   the extra triangles (9 words), the ray (6 words), the interval (2 words: each the raw bits, 0, +inf, or the
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
using raykernel::fuzz::zero_by_bits;

constexpr double inf = std::numeric_limits<double>::infinity();

struct Reader {
  const std::uint8_t* data;
  std::size_t size;
  std::size_t offset = 0;
  std::uint64_t word() {
    std::uint64_t w = 0;
    for (std::size_t k = 0; k < 8; ++k, ++offset)
      if (offset < size) w |= std::uint64_t{data[offset]} << (8 * k);
    return w;
  }
};

// One coordinate, by the tag in the word's top byte (see the header).
double choose(std::uint64_t w, const Mesh& mesh, int scale) {
  const auto tag = static_cast<std::uint8_t>(w >> 56);
  const std::uint64_t rest = w & ((std::uint64_t{1} << 56) - 1);
  if (tag < 0x40) return std::bit_cast<double>(rest | (std::uint64_t{tag} << 58));
  if (tag < 0x80) {
    const Vec3& v = mesh.vertices[rest % mesh.vertices.size()];
    const std::uint64_t axis = (rest / mesh.vertices.size()) % 3;
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
  }
  if (tag < 0xC0) return std::ldexp(static_cast<double>(static_cast<int>(rest % 17) - 8), scale - 2);
  return std::ldexp(static_cast<double>(static_cast<int>(rest % 9) - 4), scale);
}

Vec3 point(Reader& r, const Mesh& mesh, int scale) {
  const double x = choose(r.word(), mesh, scale), y = choose(r.word(), mesh, scale);
  return {x, y, choose(r.word(), mesh, scale)};
}

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
  const int scale = 4 * (((head >> 1) & 7) - 4);
  Mesh mesh = (head & 1) ? raykernel::testkit::make_subdivided_cube(1, 1) : raykernel::testkit::make_octahedron(1);
  for (Vec3& v : mesh.vertices) v = {std::ldexp(v.x, scale), std::ldexp(v.y, scale), std::ldexp(v.z, scale)};
  const TriangleRule rule = ((head >> 4) & 3) == 3 ? TriangleRule::closed : TriangleRule::owned;
  Reader r{data, size, 1};
  const int extra = (head >> 6) & 3;
  for (int k = 0; k < extra; ++k) {
    std::array<std::uint32_t, 3> t{};
    for (auto& index : t) {
      const Vec3 v = point(r, mesh, scale);
      if (!raykernel::fuzz::finite_vector_by_bits(v)) {
        index = 0;
        continue;
      }
      mesh.vertices.push_back(v);
      index = static_cast<std::uint32_t>(mesh.vertices.size() - 1);
    }
    mesh.triangles.push_back(t);
  }
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
