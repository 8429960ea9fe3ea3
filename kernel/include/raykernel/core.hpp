// raykernel/core.hpp: what every primitive shares — points and rays, the stages of the certified cascades,
// exact rationals, the error for invalid input, the floating-point environment and the version. The
// primitives are <raykernel/plane.hpp>, <raykernel/triangle.hpp>; <raykernel/raykernel.hpp> includes them all.
//
// Every answer of raykernel is exact for the doubles that were passed in (the "exact geometric computation"
// model of CGAL and Shewchuk): decided from exact signs of polynomials in the inputs, with every reported
// number the exact value rounded to the nearest double, ties to even. The certified entry points get there
// through a cascade of stages (a binary64 filter, a double-double stage, exact floating-point expansions,
// exact rationals as the last resort); the `_exact` ones use exact rationals only and are the reference the
// cascade is tested against; the `_naive` ones are textbook formulas in plain doubles, the baselines.
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

// Thrown by every certified and exact entry point for input that has no answer: a NaN or infinite
// component, a zero direction, a zero normal. what() names the offending field, e.g. "ray direction is the
// zero vector".
class invalid_input : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The reason the ray is invalid (the same text `invalid_input::what()` carries), or nothing when it is valid:
// a NaN or infinite component ("ray origin y is NaN"), or a zero direction ("ray direction is the zero
// vector"). Decided from the bits, in any floating-point environment. Each primitive adds its own
// validate overloads.
[[nodiscard]] std::optional<std::string> validate(const Ray& ray);

// ---------------------------------------------------------------------------------------------------------
// Stages and exact values, for reference use, statistics and tests.

// The stages of every certified cascade, cheapest first (kernel/src/core/ has their shared arithmetic, each
// primitive's folder its error bounds).
enum class Stage : std::uint8_t {
  filter,       // binary64 with a semi-static error bound (signs only)
  compensated,  // double-double num and den with an error bound; decides signs and the rounding of t
  expansion,    // exact floating-point expansions (Shewchuk); exact signs, near-exact num and den
  exact,        // exact rationals (GMP, CGAL::Exact_rational) and MPFR
};
inline constexpr int stage_count = 4;

// An exact rational in lowest terms, as decimal strings: denominator ≥ 1, the sign on the numerator.
struct Rational {
  std::string numerator;
  std::string denominator;
  [[nodiscard]] std::string str() const { return numerator + "/" + denominator; }
};

// The exact rational `numerator/denominator` (decimal integers, denominator nonzero) rounded to the nearest
// double, ties to even, with IEEE-754 overflow to ±inf and gradual underflow; a nonzero value that rounds
// to zero keeps its sign. Throws std::invalid_argument on malformed text. The rounding every exact t uses.
[[nodiscard]] double round_rational_to_double(std::string_view numerator, std::string_view denominator);

// row·v + c exactly, rounded once to the nearest double (ties to even, the rounding above): one coordinate of an
// affine map's image, correctly rounded — e.g. a mesh's vertices under a rotation (the scenes' "rounding":
// "nearest"). Equal inputs give equal outputs, so vertices a mesh shares, or repeats, stay shared. Throws
// std::invalid_argument when a value is not finite; the result is ±inf when the exact value rounds beyond the
// doubles.
[[nodiscard]] double round_affine(const Vec3& row, const Vec3& v, double c);

[[nodiscard]] std::string_view to_string(Stage stage) noexcept;  // "filter", "compensated", ...

// Whether this thread's floating-point environment is the one the certified stages assume: round to
// nearest, and (on x86) neither flush-to-zero nor denormals-are-zero, and no floating-point exception
// unmasked (trapping). Every entry point checks it and, when it is not, installs the default for the call
// and restores the caller's environment, status flags included, before returning (README,
// "Floating-point assumptions").
[[nodiscard]] bool floating_point_environment_is_default() noexcept;

// The library's version, "MAJOR.MINOR.PATCH".
[[nodiscard]] std::string_view version() noexcept;

}  // namespace raykernel
