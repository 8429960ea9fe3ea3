// Validation of the inputs, in one place: what makes a ray, a plane or a triangle query invalid (docs/
// contract.md §1, §6: a NaN or infinite component, a zero direction, a zero normal), decided from the
// bits of the doubles so that the answer does not depend on the floating-point environment (DAZ would
// make a subnormal compare equal to zero). The public functions (validate in raykernel.hpp and triangle.hpp)
// give the reason in words; the inline predicates here say only yes or no, for the entry points' fast checks.
#pragma once

#include <raykernel/interval.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/sphere.hpp>

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace raykernel::detail {

[[nodiscard]] inline bool is_finite(double x) noexcept {
  constexpr std::uint64_t exponent = 0x7FF0000000000000ULL;
  return (std::bit_cast<std::uint64_t>(x) & exponent) != exponent;
}
[[nodiscard]] inline bool is_zero(double x) noexcept { return (std::bit_cast<std::uint64_t>(x) << 1) == 0; }

// Whether the doubles of `x` — a Vec3, a Ray, a Plane or a Triangle: aggregates of doubles only — are all finite:
// is_finite of each, as one reduction the compiler vectorizes with SSE2's integer operations (the entry points
// check 6 to 15 doubles before their cascades). The exponent field u = bits & 0x7FF0…0 is at most 0x7FF0…0, so
// u + 2^52 reaches bit 63 exactly when u is all ones (an infinity or a NaN), and no sum carries out of 64 bits.
template <class T>
[[nodiscard]] inline bool all_finite(const T& x) noexcept {
  static_assert(sizeof(T) % sizeof(double) == 0 && alignof(T) == alignof(double));
  constexpr std::size_t n = sizeof(T) / sizeof(double);
  constexpr std::uint64_t exponent = 0x7FF0000000000000ULL, unit = std::uint64_t{1} << 52;
  const auto bits = std::bit_cast<std::array<std::uint64_t, n>>(x);
  std::uint64_t any = 0;
  for (std::size_t i = 0; i < n; ++i) any |= (bits[i] & exponent) + unit;
  return (any >> 63) == 0;
}
static_assert(sizeof(Vec3) == 3 * sizeof(double) && sizeof(Ray) == 2 * sizeof(Vec3) &&
              sizeof(Plane) == 2 * sizeof(Vec3) && sizeof(Triangle) == 3 * sizeof(Vec3));
[[nodiscard]] inline bool is_finite(const Vec3& v) noexcept { return all_finite(v); }
[[nodiscard]] inline bool is_zero(const Vec3& v) noexcept { return is_zero(v.x) & is_zero(v.y) & is_zero(v.z); }

[[nodiscard]] inline bool is_valid(const Ray& r) noexcept { return all_finite(r) & !is_zero(r.direction); }
[[nodiscard]] inline bool is_valid(const Plane& p) noexcept { return all_finite(p) & !is_zero(p.normal); }
// A triangle is valid when its vertices are finite; a degenerate one (N = 0) is valid input (docs/contract.md
// §6).
[[nodiscard]] inline bool is_valid(const Triangle& t) noexcept { return all_finite(t); }

// From the bits: positive and not zero (a positive subnormal counts; −0 does not).
[[nodiscard]] inline bool is_positive(double x) noexcept {
  return (std::bit_cast<std::uint64_t>(x) >> 63) == 0 && !is_zero(x);
}
// A sphere is valid when its centre is finite and its radius finite and positive (docs/contract.md §10).
[[nodiscard]] inline bool is_valid(const Sphere& s) noexcept {
  return is_finite(s.center) & is_finite(s.radius) & is_positive(s.radius);
}

// A ray's interval (docs/contract.md §8): 0 ≤ t_min ≤ t_max ≤ +inf, t_min finite, no NaN; −0 is 0. From the bits:
// for doubles that are not NaN and not negative, the order of the values is the order of their bit patterns
// (−0 is read as +0 first), whatever the floating-point environment.
[[nodiscard]] inline bool is_valid(const RayInterval& interval) noexcept {
  const std::uint64_t magnitude_mask = 0x7FFFFFFFFFFFFFFFULL, infinity = 0x7FF0000000000000ULL;
  const std::uint64_t lo = std::bit_cast<std::uint64_t>(interval.t_min), hi = std::bit_cast<std::uint64_t>(interval.t_max);
  const std::uint64_t lo_magnitude = lo & magnitude_mask, hi_magnitude = hi & magnitude_mask;
  const bool lo_negative = (lo >> 63) != 0 && lo_magnitude != 0, hi_negative = (hi >> 63) != 0 && hi_magnitude != 0;
  return lo_magnitude < infinity && hi_magnitude <= infinity && !lo_negative && !hi_negative &&
         lo_magnitude <= hi_magnitude;
}
// Throws invalid_input with validate(interval)'s reason (raykernel/occlusion.hpp).
void throw_if_invalid_interval(const RayInterval& interval);

// The reason a vector named `name` is not finite ("ray origin y is NaN", "plane normal x is -inf"), or
// nothing.
[[nodiscard]] std::optional<std::string> non_finite_reason(const char* name, const Vec3& v);

}  // namespace raykernel::detail
