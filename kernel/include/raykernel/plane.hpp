// raykernel/plane.hpp: exact ray–plane intersection for binary64 inputs (docs/contract.md §1–§2).
//
// The relation is decided from the exact signs of
//
//     den = d·n        and        num = (p − o)·n,
//
// evaluated over the reals, and t is the exact rational num/den rounded to the nearest double, ties to
// even. `intersect` gets there through the certified cascade (kernel/src/plane/); `intersect_exact` uses exact
// rationals only (CGAL::Exact_rational, MPFR for the rounding) and is the reference; `intersect_naive` is the
// lecture's formula in plain doubles: the baseline, without guarantees.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/interval.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace raykernel {

// The plane {x : (x − point)·normal = 0}. The normal need not be unit length.
struct Plane {
  Vec3 point, normal;
};

enum class Relation : std::uint8_t {
  hit,       // den ≠ 0 and num/den ≥ 0: the ray meets the plane at t = num/den (t = 0: origin on the plane)
  behind,    // den ≠ 0 and num/den < 0: the line meets the plane behind the origin
  parallel,  // den = 0 and num ≠ 0: no point of the line lies on the plane
  in_plane,  // den = 0 and num = 0: the whole ray lies in the plane
};

// t is the exact num/den rounded to nearest, ties to even (±inf beyond the double range; a nonzero t that
// rounds to zero keeps its sign; an exact zero is +0). t is NaN for parallel and in_plane.
struct Intersection {
  Relation relation;
  double t;
};

// The reason the input is invalid (the same text `invalid_input::what()` carries), or nothing when it is
// valid (see validate(const Ray&) in core.hpp): with a plane, a NaN or infinite component ("plane normal x
// is -inf") or a zero normal. With a ray and a plane, every non-finite component is reported before a zero
// vector.
[[nodiscard]] std::optional<std::string> validate(const Plane& plane);
[[nodiscard]] std::optional<std::string> validate(const Ray& ray, const Plane& plane);

// The certified intersection: the exact answer of docs/contract.md §1, computed by the cheapest stage whose
// certified error bound decides it. Thread-safe; no global state. Right in any floating-point environment
// the caller left (rounding mode, flush-to-zero, denormals-are-zero, trap masks), which it leaves exactly
// as it found it. Throws invalid_input.
[[nodiscard]] Intersection intersect(const Ray& ray, const Plane& plane);

// The certified relation alone (hit, behind, parallel or in-plane), without t: the yes/no predicate
// beside the construction, as CGAL keeps `do_intersect` beside `intersection`. For random queries the
// binary64 filter decides it, at about the cost of the naive formula. Same guarantees and errors as
// `intersect`.
[[nodiscard]] Relation relation(const Ray& ray, const Plane& plane);

// The reference: exact rational arithmetic (CGAL::Exact_rational) for num and den, MPFR for the rounding of
// t. Slow (microseconds) and obviously right. Throws invalid_input.
[[nodiscard]] Intersection intersect_exact(const Ray& ray, const Plane& plane);

// docs/contract.md §8 on one plane: the intersection (as `intersect`) when the ray hits the plane at an exact t in
// `interval` ([t_min, t_max], closed; compared exactly, never through a rounded t); nothing otherwise (behind,
// parallel, in the plane, or t outside). Throws invalid_input (the ray, the plane, or the interval naming the
// bound). intersect_exact: the same in exact rationals alone.
[[nodiscard]] std::optional<Intersection> intersect(const Ray& ray, const RayInterval& interval, const Plane& plane);
[[nodiscard]] std::optional<Intersection> intersect_exact(const Ray& ray, const RayInterval& interval,
                                                          const Plane& plane);

// The seed's formula t = −((o − p)·n) / (d·n) in plain binary64, classifying with the computed values
// (d·n == 0 → parallel or in-plane, t ≥ 0 → hit). No validation, no guarantee: the baseline that the
// certified path is measured and tested against.
[[nodiscard]] Intersection intersect_naive(const Ray& ray, const Plane& plane) noexcept;

// `intersect` plus which stage decided the relation and which decided t. t_stage is the stage that
// produced t (equal to relation_stage when t needed no rounding: parallel, in-plane, or num = 0).
struct TracedIntersection {
  Intersection intersection;
  Stage relation_stage;
  Stage t_stage;
};
[[nodiscard]] TracedIntersection intersect_traced(const Ray& ray, const Plane& plane);

// `intersect_exact` plus the exact values it decided from: num and den, and t = num/den when it exists.
struct ExactIntersection {
  Intersection intersection;
  Rational num;
  Rational den;
  std::optional<Rational> t;  // set for hit and behind
};
[[nodiscard]] ExactIntersection intersect_exact_rational(const Ray& ray, const Plane& plane);

[[nodiscard]] std::string_view to_string(Relation relation) noexcept;  // "hit", "behind", "parallel", "in-plane"

}  // namespace raykernel
