// An enclosure of a real value V by a double-double and a radius: |V − (hi + lo)| ≤ radius. Stages 2 and
// 3 produce enclosures of num and den; the sign and rounding decisions below consume them, so each
// decision is written (and proved) once for every stage.
#pragma once

#include "core/eft.hpp"
#include "core/lanes.hpp"
#include "core/sign.hpp"

#include <cmath>

namespace raykernel::detail {

template <class V>
struct EnclosureT {
  V hi;
  V lo;
  V radius;  // ≥ 0; +inf or NaN means "no information" (an overflow happened)
};
using Enclosure = EnclosureT<double>;

// enclosure_sign: with (v, e) = TwoSum(hi, lo), |V − v| ≤ |e| + radius ≤ u|v| + radius, so
// |v| > 2·radius ⇒ sign(V) = sign(v). Never certifies zero (an enclosure of positive radius cannot).
//   Certified by: proofs/plane/PlaneCompensated.v, `enclosure_sign_sound`.
// Per lane and branch-free, as dot3_filter: uncertain also when the radius is +inf or NaN.
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline IntegerOf<V> enclosure_sign_lanes(const EnclosureT<V>& e) noexcept {
  const V v = e.hi + e.lo;                 // the hi part of TwoSum(hi, lo): one rounding
  const V twice_radius = e.radius + e.radius;  // exact, or +inf
  return sign_lanes(v > twice_radius, v < -twice_radius);
}

[[nodiscard]] inline Sign enclosure_sign(const Enclosure& e) noexcept {
  return static_cast<Sign>(enclosure_sign_lanes(e));
}

}  // namespace raykernel::detail
