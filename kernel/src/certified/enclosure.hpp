// An enclosure of a real value V by a double-double and a radius: |V − (hi + lo)| ≤ radius. Stages 2 and
// 3 produce enclosures of num and den; the sign and rounding decisions below consume them, so each
// decision is written (and proved) once for every stage.
#pragma once

#include "certified/eft.hpp"
#include "certified/sign.hpp"

#include <cmath>

namespace raykernel::detail {

struct Enclosure {
  double hi;
  double lo;
  double radius;  // ≥ 0; +inf or NaN means "no information" (an overflow happened)
};

// enclosure_sign: with (v, e) = TwoSum(hi, lo), |V − v| ≤ |e| + radius ≤ u|v| + radius, so
// |v| > 2·radius ⇒ sign(V) = sign(v). Never certifies zero (an enclosure of positive radius cannot).
//   Certified by: proofs/Compensated.v, `enclosure_sign_sound`.
[[nodiscard]] inline Sign enclosure_sign(const Enclosure& e) noexcept {
  const double v = e.hi + e.lo;  // the hi part of TwoSum(hi, lo): one rounding
  const double twice_radius = e.radius + e.radius;  // exact, or +inf
  if (v > twice_radius) return Sign::positive;
  if (v < -twice_radius) return Sign::negative;
  return Sign::uncertain;
}

}  // namespace raykernel::detail
