// The neighbours of a double: IEEE 754's nextUp and nextDown, Flocq's Bsucc and Bpred, from the bits (integer
// operations only: no rounding, no flag, whatever the floating-point environment; no call into libm, whose
// nextafter branches on the data).
//   Valid range: any double but NaN.
//   Error bound: none (exact).
//   Certified by: the proofs that use them model them as Flocq's Bsucc and Bpred:
//   proofs/core/QuotientBoundary.v, `round_quotient_at_boundaries_sound`
//   proofs/core/IntervalWidening.v, `ieee_sign_sound`
//   and the bits are checked against std::nextafter towards ±inf by tests/closest_point_test.cpp (zeros,
//   subnormals, normals, the largest finite doubles, infinities).
#pragma once

#include <bit>
#include <cstdint>

namespace raykernel::detail {

// The smallest double above x (x not NaN): +0 and −0 give 2^-1074, −inf gives −DBL_MAX, +inf stays.
[[nodiscard]] inline double next_up(double x) noexcept {
  auto bits = std::bit_cast<std::uint64_t>(x);
  if (bits == 0x8000000000000000u) bits = 0;          // −0 steps like +0
  if (bits == 0x7FF0000000000000u) return x;          // +inf stays
  // +1 for x ≥ +0 (+0 gives 2^-1074), −1 for x < 0 (−inf gives −DBL_MAX).
  bits += 1 - ((bits >> 63) << 1);
  return std::bit_cast<double>(bits);
}

// The largest double below x (x not NaN): −next_up(−x).
[[nodiscard]] inline double next_down(double x) noexcept { return -next_up(-x); }

}  // namespace raykernel::detail
