// The certified ray–sphere cascade (docs/contract.md §10): the expansion stage (ray_sphere_stages.hpp) for the
// signs of C and D and for each root's rounding, the exact stage (exact_sphere.hpp) for whatever it leaves.
// Valid input, the default floating-point environment (the entry points in sphere_api.cpp see to both).
#pragma once

#include <raykernel/interval.hpp>
#include <raykernel/sphere.hpp>

#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace raykernel::detail {

// The answer is written to `out` (so that a caller's return slot receives it in place: a copy of a struct whose
// bytes were just stored one by one stalls store forwarding), the stages returned.
struct SphereStages {
  Stage relation, rounding;
};
SphereStages sphere_intersection_cascade(const Ray& ray, const Sphere& sphere, SphereIntersection& out);
// The cascade's filter stage alone, on raw input: true (and the answer in `out`, both stages the filter) when the
// filter decides the signs of C and D, the radius is positive and, unless the line misses, the boundary filter
// rounds both roots; false otherwise (then the caller validates and runs the cascade). No validation is needed
// before it, for the reason given at fast_sphere_relation below.
[[nodiscard]] bool sphere_intersection_filtered(const Ray& ray, const Sphere& sphere, SphereIntersection& out) noexcept;
// The cascade after its filter stage answered nothing (valid input): the caller that tried
// sphere_intersection_filtered goes on here without running it again.
SphereStages sphere_intersection_after_filter(const Ray& ray, const Sphere& sphere, SphereIntersection& out);
[[nodiscard]] inline TracedSphereIntersection sphere_intersection_cascade(const Ray& ray, const Sphere& sphere) {
  TracedSphereIntersection r;
  const SphereStages stages = sphere_intersection_cascade(ray, sphere, r.intersection);
  r.relation_stage = stages.relation;
  r.rounding_stage = stages.rounding;
  return r;
}

struct TracedSphereClassification {
  SphereClassification classification;
  Stage stage;
};
[[nodiscard]] TracedSphereClassification sphere_relation_cascade(const Ray& ray, const Sphere& sphere);

// The relation's fast path, on raw input: the binary64 filter's signs of C and D when both are certain and the
// radius is positive; nothing otherwise (then the caller validates and runs the cascade). No validation is
// needed before it: certain signs imply finite input and d ≠ 0. Every component of o, c and r reaches C's bound
// through |f|² + r² (f = o − c), so a NaN or infinite one makes that bound NaN or +inf, which certifies
// nothing; one of d makes A and its bound NaN or infinite, hence D's bound (t3 = e_A·|C|, t4 = (|A| + e_A)·e_C);
// d = 0 makes A = B = D̂ = 0 exactly, and a zero is never certified. The radius is the one condition the filter
// cannot see (r and −r have the same r²), checked here. tests/sphere_test.cpp (SphereFastPath) checks every
// kind of invalid input goes to validation.
// The answer is packed in one integer, decoded by fast_sphere_relation: the origin in bits 0–7, the relation in
// bits 8–15, bit 16 set when certain (GCC assembles an optional of two one-byte enums through the stack, and reading
// it back stalled store forwarding: half the function's time, measured).
inline constexpr std::uint32_t fast_sphere_relation_certain = 1u << 16;
[[nodiscard]] std::uint32_t fast_sphere_relation_packed(const Ray& ray, const Sphere& sphere) noexcept;
// The packed answer's two low bytes are a SphereClassification's (origin, then relation) on a little-endian
// machine; elsewhere it is assembled field by field.
[[nodiscard]] inline SphereClassification unpack_sphere_classification(std::uint32_t p) noexcept {
  static_assert(sizeof(SphereClassification) == 2 && offsetof(SphereClassification, relation) == 1);
  if constexpr (std::endian::native == std::endian::little)
    return std::bit_cast<SphereClassification>(static_cast<std::uint16_t>(p));
  else
    return SphereClassification{static_cast<SphereOrigin>(p & 0xffu), static_cast<SphereRelation>((p >> 8) & 0xffu)};
}
[[nodiscard]] inline std::optional<SphereClassification> fast_sphere_relation(const Ray& ray, const Sphere& sphere) noexcept {
  const std::uint32_t p = fast_sphere_relation_packed(ray, sphere);
  if ((p & fast_sphere_relation_certain) == 0) return std::nullopt;
  return unpack_sphere_classification(p);
}

// sign(t_root − b) for a root of a sphere the ray's line meets (root −1: t1, or the tangent root t0; +1: t2) and a
// double b: the expansion stage's side of b (sphere_root_side with the boundary m = (b + b)/2 = b), else the exact
// stage's (exact::root_side_of_midpoint).
[[nodiscard]] int sphere_root_side_of(const Ray& ray, const Sphere& sphere, int root, double b);

// The hit of a sphere within a ray's interval (docs/contract.md §8 and §10: the smallest root t with
// t_min ≤ t ≤ t_max, the tangent root included), from the cascade's answer `r` (its roots correctly rounded):
// which root (−1: t1 or t0, +1: t2) and RN of it; nothing when no root lies in the interval. Each root is
// compared with a bound b by its rounding first — RN is monotone and RN(b) = b, so RN(t) < b implies t < b and
// RN(t) > b implies t > b (proofs/core/RoundOrder.v, `rn_strict_order`) — and by sphere_root_side_of only when
// RN(t) = b. A valid interval (the caller validates it).
struct SphereRootHit {
  int root;
  double t;
};
[[nodiscard]] std::optional<SphereRootHit> sphere_hit_in_interval(const Ray& ray, const Sphere& sphere,
                                                                  const SphereIntersection& r,
                                                                  const RayInterval& interval);

// Whether the sphere meets the open segment from p to q (docs/contract.md §8 and §10; p ≠ q, valid input): the
// binary64 filter's signs of C_p = |p − c|² − r² and C_q = |q − c|² − r² decide when they differ (the quadratic
// changes sign between the ends: a root strictly inside) or are both negative (it is negative on all of [0, 1],
// being convex: no root there); otherwise the exact stage (exact::segment_meets_sphere).
//   Certified by: proofs/sphere/SphereSegment.v, `segment_ends_opposite_meet` and `segment_ends_inside_clear`
//   (the two shortcuts; the filter's signs by proofs/sphere/SphereFilter.v, `sphere_filter_c_sound`).
[[nodiscard]] bool segment_meets_sphere(const Vec3& p, const Vec3& q, const Sphere& sphere);

}  // namespace raykernel::detail
