// The steps of a spawned origin (docs/contract.md §9, and the sphere's rule in docs/contract.md): the origin's
// format, its finite values in order (ordinals: one zero, as nextafter walks them), and the checks and messages
// every spawn entry point shares — written once, for the triangle's spawn (spawn.cpp) and the sphere's
// (sphere/sphere_spawn.cpp).
#pragma once

#include <raykernel/spawn.hpp>

#include "core/binary64_rounding.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

namespace raykernel::detail::spawn_steps {

inline const char* axis_name(int i) { return i == 0 ? "x" : i == 1 ? "y" : "z"; }

[[noreturn]] inline void invalid(const std::string& reason) { throw invalid_input(reason); }

// The first non-finite component of v ("WHAT x is NaN"), or nothing.
inline void require_finite(const Vec3& v, const char* what) {
  const double c[3] = {v.x, v.y, v.z};
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k]))
      invalid(std::string(what) + " " + axis_name(k) + " is " + (std::isnan(c[k]) ? "NaN" : c[k] > 0 ? "inf" : "-inf"));
}

inline const exact::BinaryFormat& format_of(OriginFormat f) {
  return f == OriginFormat::binary32 ? exact::binary32_format : exact::binary64_format;
}

// The position of a value of the format among its finite values in increasing order, with one zero (−0 and +0
// are both 0): the magnitude's bits, negated for negative values. Consecutive values have consecutive ordinals,
// in both formats (binary32 values are read from their float bits).
// Finite values have magnitudes below 2^63 as bits, so an ordinal fits in a std::int64_t.
inline std::int64_t ordinal(double x, OriginFormat f) {
  const std::uint64_t magnitude = f == OriginFormat::binary32
                                      ? std::bit_cast<std::uint32_t>(static_cast<float>(std::fabs(x)))
                                      : std::bit_cast<std::uint64_t>(std::fabs(x));
  return x < 0 ? -static_cast<std::int64_t>(magnitude) : static_cast<std::int64_t>(magnitude);
}

// The ordinal of the largest finite value of the format (its bits: below 2^63).
inline std::uint64_t largest_ordinal(OriginFormat f) {
  return f == OriginFormat::binary32 ? std::uint64_t{0x7f7fffff} : std::uint64_t{0x7fefffffffffffff};
}

// The value of the format with ordinal n, or ±inf beyond the largest finite value.
inline double from_ordinal(std::int64_t n, OriginFormat f) {
  const std::uint64_t magnitude = n < 0 ? static_cast<std::uint64_t>(-n) : static_cast<std::uint64_t>(n);
  double x;
  if (f == OriginFormat::binary32)
    x = magnitude > 0x7f7fffff ? HUGE_VAL
                               : static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(magnitude)));
  else
    x = magnitude > 0x7fefffffffffffff ? HUGE_VAL : std::bit_cast<double>(magnitude);
  return n < 0 ? -x : x;
}

// The next value of the format after x in direction δ (±1), or ±inf past the largest finite value.
inline double step(double x, int delta, OriginFormat f) { return from_ordinal(ordinal(x, f) + delta, f); }

// k = |ordinal(to) − ordinal(from)| < 2^64: the unsigned difference of the larger and the smaller is exact.
inline std::uint64_t steps_between(double from, double to, OriginFormat f) {
  const std::int64_t a = ordinal(from, f), b = ordinal(to, f);
  return b > a ? static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a)
               : static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b);
}

}  // namespace raykernel::detail::spawn_steps
