// Stage 2 of the certified cascade: a 3-term dot product in double-double (Ogita–Rump–Oishi "Dot2" with
// FMA-based TwoProduct), enclosed by an a-priori error bound of order u²·Σ|a_i b_i|. It decides the signs
// stage 1 could not (unless the value is within ~2^-100 of the terms' magnitude) and gives the enclosures
// from which round_quotient rounds t correctly. Cost over stage 1: 6 FMA, 2 TwoSum, 5 add.
#pragma once

#include "certified/dot3_filter.hpp"
#include "certified/eft.hpp"
#include "certified/enclosure.hpp"
#include "certified/error_bounds.hpp"

#include <cmath>

namespace raykernel::detail {

// compensated_dot3: an enclosure of V = Σ (a_i + α_i)·b_i, where a_i are the values stage 1 multiplied
// (stage1.product[i] == a_i ⊗ b_i) and α_i their exact low parts, |α_i| ≤ u|a_i| (zero for den; the TwoSum
// error of p_i ⊖ o_i for num).
//   Error bound: |V − (hi + lo)| ≤ (2^-101 ⊗ m) ⊕ 2^-1070, m the stage-1 magnitude (error_bounds.hpp).
//   Valid range: all finite inputs; the radius is not finite if anything overflowed.
//   Certified by: proofs/Compensated.v, `compensated_dot3_enclosure`.
[[nodiscard]] inline Enclosure compensated_dot3(const double a[3], const double alpha[3], const double b[3],
                                                const Dot3Rounded& stage1) noexcept {
  double g[3];
  for (int i = 0; i < 3; ++i) {
    const double h = stage1.product[i];
    const double l = std::fma(a[i], b[i], -h);  // l_i = RN(a_i b_i − h_i): exact unless a_i b_i underflows
    g[i] = std::fma(alpha[i], b[i], l);         // g_i = RN(α_i b_i + l_i)
  }
  const DoubleDouble s2 = two_sum(stage1.product[0], stage1.product[1]);
  const DoubleDouble s3 = two_sum(s2.hi, stage1.product[2]);
  const double lo = ((g[0] + g[1]) + g[2]) + (s2.lo + s3.lo);
  const double radius = bounds::compensated_relative * stage1.magnitude + bounds::compensated_absolute;
  // A NaN or infinite hi/lo (an overflow inside TwoSum or the FMAs) must reach the decisions as "no
  // information": fold it into the radius, which every decision compares against.
  const bool finite = std::isfinite(s3.hi) && std::isfinite(lo);
  return {s3.hi, lo, finite ? radius : HUGE_VAL};
}

}  // namespace raykernel::detail
