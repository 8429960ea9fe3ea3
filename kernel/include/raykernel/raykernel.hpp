// raykernel: exact ray–plane intersection for binary64 inputs.
//
// Every answer is exact for the doubles that were passed in (the "exact geometric computation" model of
// CGAL and Shewchuk): the relation is decided from the exact signs of
//
//     den = d·n        and        num = (p − o)·n,
//
// evaluated over the reals, and t is the exact rational num/den rounded to the nearest double, ties to
// even (docs/contract.md §1). `intersect` gets there through a cascade of certified stages (a binary64 filter,
// a double-double stage, exact floating-point expansions, and CGAL's exact rationals with MPFR rounding as
// the last resort); `intersect_exact` uses exact rationals only and is the reference the cascade is tested
// against. `intersect_naive` is the lecture's formula in plain doubles: the baseline, without guarantees.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace raykernel {

struct Vec3 {
  double x, y, z;
};

// A half-line {origin + t·direction : t ≥ 0}. The direction need not be unit length.
struct Ray {
  Vec3 origin, direction;
};

// The plane {x : (x − point)·normal = 0}. The normal need not be unit length.
struct Plane {
  Vec3 point, normal;
};

// The triangle with vertices a, b, c (docs/contract.md §6). Its orientation is the order of the vertices:
// the normal N = (b − a) × (c − a). Degenerate triangles (collinear or repeated vertices) are valid input.
struct Triangle {
  Vec3 a, b, c;
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

// Thrown by `intersect` and `intersect_exact` for input that has no answer: a NaN or infinite component,
// a zero direction, or a zero normal. what() names the offending field, e.g. "ray direction is zero".
class invalid_input : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The reason the input is invalid (the same text `invalid_input::what()` carries), or nothing when it is
// valid: a NaN or infinite component ("ray origin y is NaN", "plane normal x is -inf"), a zero direction
// ("ray direction is the zero vector") or a zero normal. Decided from the bits, in any floating-point
// environment. With a ray and a plane, every non-finite component is reported before a zero vector.
[[nodiscard]] std::optional<std::string> validate(const Ray& ray);
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

// The seed's formula t = −((o − p)·n) / (d·n) in plain binary64, classifying with the computed values
// (d·n == 0 → parallel or in-plane, t ≥ 0 → hit). No validation, no guarantee: the baseline that the
// certified path is measured and tested against.
[[nodiscard]] Intersection intersect_naive(const Ray& ray, const Plane& plane) noexcept;

// ---------------------------------------------------------------------------------------------------------
// Stages and exact values, for reference use, statistics and tests.

// The stages of `intersect`, cheapest first. See kernel/src/certified/ for each one's error bound.
enum class Stage : std::uint8_t {
  filter,       // binary64 with a semi-static error bound (signs only)
  compensated,  // double-double num and den with an error bound; decides signs and the rounding of t
  expansion,    // exact floating-point expansions (Shewchuk); exact signs, near-exact num and den
  exact,        // CGAL::Exact_rational and MPFR
};
inline constexpr int stage_count = 4;

// `intersect` plus which stage decided the relation and which decided t. t_stage is the stage that
// produced t (equal to relation_stage when t needed no rounding: parallel, in-plane, or num = 0).
struct TracedIntersection {
  Intersection intersection;
  Stage relation_stage;
  Stage t_stage;
};
[[nodiscard]] TracedIntersection intersect_traced(const Ray& ray, const Plane& plane);

// An exact rational in lowest terms, as decimal strings: denominator ≥ 1, the sign on the numerator.
struct Rational {
  std::string numerator;
  std::string denominator;
  [[nodiscard]] std::string str() const { return numerator + "/" + denominator; }
};

// `intersect_exact` plus the exact values it decided from: num and den, and t = num/den when it exists.
struct ExactIntersection {
  Intersection intersection;
  Rational num;
  Rational den;
  std::optional<Rational> t;  // set for hit and behind
};
[[nodiscard]] ExactIntersection intersect_exact_rational(const Ray& ray, const Plane& plane);

// The exact rational `numerator/denominator` (decimal integers, denominator nonzero) rounded to the nearest
// double, ties to even, with IEEE-754 overflow to ±inf and gradual underflow; a nonzero value that rounds
// to zero keeps its sign. Throws std::invalid_argument on malformed text. The rounding every exact t uses.
[[nodiscard]] double round_rational_to_double(std::string_view numerator, std::string_view denominator);

[[nodiscard]] std::string_view to_string(Relation relation) noexcept;  // "hit", "behind", "parallel", "in-plane"
[[nodiscard]] std::string_view to_string(Stage stage) noexcept;        // "filter", "compensated", ...

// Whether this thread's floating-point environment is the one the certified stages assume: round to
// nearest, and (on x86) neither flush-to-zero nor denormals-are-zero, and no floating-point exception
// unmasked (trapping). Every entry point checks it and, when it is not, installs the default for the call
// and restores the caller's environment, status flags included, before returning (README,
// "Floating-point assumptions").
[[nodiscard]] bool floating_point_environment_is_default() noexcept;

// The library's version, "MAJOR.MINOR.PATCH".
[[nodiscard]] std::string_view version() noexcept;

}  // namespace raykernel
