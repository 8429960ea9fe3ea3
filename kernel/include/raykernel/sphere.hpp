// raykernel/sphere.hpp: exact ray–sphere intersection (docs/contract.md §10), with correctly rounded roots.
//
// For a ray (origin o, direction d) and a sphere (centre c, radius r), every answer is exact for the doubles
// given. Over the reals, with f = o − c:
//
//     A = d·d,   B = d·f,   C = f·f − r²,   D = B² − A·C   (a quarter of the discriminant),
//
// the origin is inside (C < 0), on the surface (C = 0) or outside (C > 0); the line misses (D < 0), touches
// (D = 0: one root t0 = −B/A) or crosses (D > 0: t1 = (−B − √D)/A < t2 = (−B + √D)/A). Each root is the exact,
// generally irrational value rounded to the nearest double, ties to even (an exact zero is +0; a nonzero root
// that rounds to zero keeps its sign; overflow gives ±inf). The exact roots are U ∓ √V with the rationals
// U = −B/A and V = D/A².
//
// `intersect` answers through a certified cascade (exact floating-point expansions for the signs of C and D
// and for the sides of each root against its rounding boundaries, exact rationals last); `intersect_exact`
// uses exact rationals and MPFR only (the reference); `intersect_naive` is the textbook quadratic formula in
// plain doubles (the baseline, without guarantees); `relation` decides the origin and the relation without
// rounding anything.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/interval.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel {

// The sphere with centre `center` and radius `radius` (> 0, finite): a closed surface (docs/contract.md §10).
struct Sphere {
  Vec3 center;
  double radius;
};

// Where the ray's origin lies: the sign of C = |o − c|² − r².
enum class SphereOrigin : std::uint8_t {
  inside,      // C < 0
  on_surface,  // C = 0
  outside,     // C > 0
};

// How the ray's line meets the sphere: the sign of D = B² − A·C.
enum class SphereRelation : std::uint8_t {
  miss,     // D < 0: no real root
  tangent,  // D = 0: one root t0 = −B/A
  cross,    // D > 0: two roots t1 < t2
};

// The relation-only answer: no root, no rounding.
struct SphereClassification {
  SphereOrigin origin;
  SphereRelation relation;
};

struct SphereIntersection {
  SphereOrigin origin;
  SphereRelation relation;
  double t1;  // RN(t1) for cross, RN(t0) for tangent; NaN for miss
  double t2;  // RN(t2) for cross, RN(t0) for tangent; NaN for miss
};

// The exact roots U ∓ √V (docs/contract.md §10): U = −B/A, V = D/A² (0 for tangent); absent for miss.
struct ExactSphereIntersection {
  SphereOrigin origin;
  SphereRelation relation;
  std::optional<Rational> u;
  std::optional<Rational> v;
};

// The reason `ray`/`sphere` are invalid input (a NaN or infinite component, a zero direction, a radius that
// is not positive), or nothing.
[[nodiscard]] std::optional<std::string> validate(const Ray& ray, const Sphere& sphere);
// The reason a sphere alone is invalid (a non-finite centre or radius, a radius that is not positive), or nothing.
[[nodiscard]] std::optional<std::string> validate(const Sphere& sphere);

// The certified answer of docs/contract.md §10. Thread-safe; answers in the default floating-point
// environment whatever the caller's. Throws invalid_input.
[[nodiscard]] SphereIntersection intersect(const Ray& ray, const Sphere& sphere);

// The origin's location and the line's relation alone (certified, nothing rounded).
[[nodiscard]] SphereClassification relation(const Ray& ray, const Sphere& sphere);

// The reference: exact rationals for A, B, C, D, each root rounded from an enclosure MPFR narrows until
// both ends round alike (a rational root, √V rational, is rounded directly). Throws invalid_input.
[[nodiscard]] SphereIntersection intersect_exact(const Ray& ray, const Sphere& sphere);
[[nodiscard]] ExactSphereIntersection intersect_exact_rational(const Ray& ray, const Sphere& sphere);

// The textbook formula in plain doubles (h = d·f, disc = h² − a·c, t = (−h ∓ √disc)/a), in the caller's
// environment: the baseline users compare, without guarantees, never throws (NaN in, NaN out).
[[nodiscard]] SphereIntersection intersect_naive(const Ray& ray, const Sphere& sphere) noexcept;

// `intersect` plus the stages that decided: the relation (the signs of C and D), and the roots (the latest
// stage any root needed; the relation's stage for miss).
struct TracedSphereIntersection {
  SphereIntersection intersection;
  Stage relation_stage;
  Stage rounding_stage;
};
[[nodiscard]] TracedSphereIntersection intersect_traced(const Ray& ray, const Sphere& sphere);

class MeshBvh;  // raykernel/bvh.hpp

// Spheres prepared for the nearest hit of a scene (raykernel/nearest_scene.hpp): validated once, in order, and,
// from `bvh_min_spheres` spheres on, a bounding volume hierarchy over their boxes (each box [c − r, c + r] rounded
// outwards, so that it holds its sphere exactly), which the nearest hit and occluded walk instead of the list.
class SphereSet {
 public:
  // Throws invalid_input naming the first invalid sphere ("sphere 3: sphere radius is not positive").
  explicit SphereSet(std::span<const Sphere> spheres);

  [[nodiscard]] std::size_t size() const noexcept { return spheres_.size(); }
  [[nodiscard]] std::span<const Sphere> spheres() const noexcept { return spheres_; }
  // The hierarchy (leaf ranges index spheres()), or null: fewer than bvh_min_spheres spheres, or a box that
  // overflows (a sphere reaching beyond the doubles); then the set is searched in order.
  [[nodiscard]] const MeshBvh* bvh() const noexcept { return bvh_.get(); }
  static constexpr std::size_t bvh_min_spheres = 8;

 private:
  std::vector<Sphere> spheres_;
  std::shared_ptr<const MeshBvh> bvh_;
};

// ---- rays with an interval (docs/contract.md §8 and §10) ------------------------------------------------------
// A sphere is closed: it blocks a ray when a root (the tangent root included) lies in the ray's interval
// [t_min, t_max], compared exactly (each root's rounding against the bound, and when they are equal the sign of
// the quadratic and its slope at the bound); its hit is the smallest such root.

// RN of the smallest root of `sphere` in `interval`, or nothing. Throws invalid_input (the ray, the sphere, the
// interval). Right in any floating-point environment.
[[nodiscard]] std::optional<double> nearest_root(const Ray& ray, const RayInterval& interval, const Sphere& sphere);

// The nearest sphere of a set within an interval: its index and RN of its root, an exact tie to the smaller index.
struct SphereHit {
  std::size_t sphere;
  double t;
};
[[nodiscard]] std::optional<SphereHit> nearest_hit(const Ray& ray, const RayInterval& interval, const SphereSet& spheres);

// Whether some sphere of the set has a root in the interval (any-hit: stops at the first).
[[nodiscard]] bool occluded(const Ray& ray, const RayInterval& interval, const SphereSet& spheres);

// ---- segments (docs/contract.md §8 and §10) --------------------------------------------------------------------
// The open segment from p to q: the line p + t·(q − p) with q − p taken exactly (never rounded), 0 < t < 1. A
// sphere meets it when a root (the tangent root included) lies strictly between the ends; an end on the sphere
// does not count by itself. Throws invalid_input for non-finite coordinates, p = q (as values) or an invalid
// sphere. Right in any floating-point environment.
[[nodiscard]] bool segment_meets(const Vec3& p, const Vec3& q, const Sphere& sphere);
[[nodiscard]] bool segment_meets_exact(const Vec3& p, const Vec3& q, const Sphere& sphere);  // the reference (GMP)
// Whether some sphere of the set meets the open segment (any-hit: stops at the first).
[[nodiscard]] bool occluded(const Vec3& p, const Vec3& q, const SphereSet& spheres);

// The references: every root and bound in rationals (roots as U ∓ √V; no rounding before the answer).
[[nodiscard]] std::optional<SphereHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval,
                                                         std::span<const Sphere> spheres);

[[nodiscard]] std::string_view to_string(SphereOrigin origin) noexcept;      // "inside", "on-surface", "outside"
[[nodiscard]] std::string_view to_string(SphereRelation relation) noexcept;  // "miss", "tangent", "cross"

}  // namespace raykernel
