// The certified fast path of spawn and spawn_to (docs/contract.md §9): the same answer as the exact path
// (spawn.cpp, GMP and MPFR), from the shared stages, or nothing — then the exact path decides (and names what is
// invalid). Derivations, ranges and theorems: spawn_certified.cpp.
#pragma once

#include "core/absolute_terms.hpp"
#include "core/dot3_compensated.hpp"
#include "core/eft.hpp"
#include "core/enclosure.hpp"

#include <raykernel/spawn.hpp>

#include <cmath>
#include <optional>

namespace raykernel::bounds {

// midpoint_offset — an enclosure of M = x + y − 2·o for doubles x, y, o (below, raykernel::detail)
//
// Formula: (s, e) = TwoSum(x, y), (h, l) = TwoSum(s, −(2 ⊗ o)), lo = l ⊕ e, radius = R ⊗ |lo|.
// Error bound: |M − (h + lo)| ≤ radius with R = 2^-52: both TwoSums and 2·o are exact, so M − (h + lo) is the
//   one rounding error of l ⊕ e: at most 2^-53·|lo| when |lo| ≥ 2^-1022, and 0 below (a sum of doubles in the
//   subnormal range is exact); R ⊗ |lo| ≥ 2^-53·|lo| for |lo| ≥ 2^-1022 (the product loses at most 2^-1075).
// Valid range: every finite x, y, o with finite results; an overflow makes a component infinite or NaN, and the
//   comparison that consumes the enclosure is then uncertain.
// Certified by: proofs/spawn/SpawnRounding.v, `midpoint_offset_encloses`; for the bits, the twin of
//   proofs/spawn/SpawnTwins.v, `midpoint_offset_twin_sound` (finite results: the model's values, so the enclosure
//   holds for them), compared with this code bit for bit by the differential runner (routine midpoint_offset,
//   group spawn).
inline constexpr double midpoint_offset_relative = 0x1p-52;

// affine_enclosure — an enclosure of X = o·D + d·N for doubles o, d and enclosures of D and N (below,
// raykernel::detail)
//
// Formula: (D_h, D_l) = TwoSum(D.hi, D.lo), (N_h, N_l) = TwoSum(N.hi, N.lo); (hi, lo, E) = compensated_dot3 of
//          a = (D_h, N_h, 0), α = (D_l, N_l, 0), b = (o, d, 0) (core/dot3_compensated.hpp);
//          radius = (C ⊗ (((|o| ⊗ D.radius) ⊕ (|d| ⊗ N.radius)) ⊕ E)) ⊕ U.
// Error bound: |X − (hi + lo)| ≤ radius with C = 1 + 2^-50, U = 2^-1060. The renormalized pairs have
//   |α_i| ≤ u|a_i| and the same sums, so compensated_dot3 encloses V = o·(D.hi + D.lo) + d·(N.hi + N.lo) within E;
//   |X − V| ≤ |o|·D.radius + |d|·N.radius. The computed radius is at least the sum of the two: four roundings
//   lose at most a factor (1 − u)^4, which C = 1 + 8u more than makes up, and the products' underflow (at most
//   2^-1075 each) is covered by U.
// Valid range: every input; a non-finite value makes the radius +inf or NaN, and round_quotient uncertain.
// Certified by: proofs/spawn/SpawnAffine.v, `affine_enclosure_sound` (from proofs/plane/PlaneCompensated.v,
//   `compensated_dot3_enclosure`); for the bits, the twin of
//   proofs/spawn/SpawnTwins.v, `affine_enclosure_twin_sound` (finite results: the model's values, so the enclosure
//   holds for them; it calls the twin of compensated_dot3, proofs/plane/PlaneTwins.v, `compensated_dot3_twin`),
//   compared with this code bit for bit by the differential runner (routine affine_enclosure, group spawn).
inline constexpr double affine_propagation_factor = 1 + 0x1p-50;
inline constexpr double affine_absolute = 0x1p-1060;

}  // namespace raykernel::bounds

namespace raykernel::detail {

// midpoint_offset (raykernel::bounds::midpoint_offset_relative above): an enclosure of x + y − 2·o.
[[nodiscard]] inline Enclosure midpoint_offset(double x, double y, double o) noexcept {
  const DoubleDouble s = two_sum(x, y);
  const DoubleDouble h = two_sum(s.hi, -(2 * o));
  const double lo = h.lo + s.lo;
  return {h.hi, lo, raykernel::bounds::midpoint_offset_relative * std::fabs(lo)};
}

// affine_enclosure (raykernel::bounds::affine_propagation_factor above): an enclosure of o·D + d·N.
[[nodiscard]] [[gnu::always_inline]] inline Enclosure affine_enclosure(double o, const Enclosure& D, double d,
                                                                     const Enclosure& N) noexcept {
  const DoubleDouble dd = two_sum(D.hi, D.lo), nn = two_sum(N.hi, N.lo);
  const double a[3] = {dd.hi, nn.hi, 0}, alpha[3] = {dd.lo, nn.lo, 0}, b[3] = {o, d, 0};
  const Enclosure v = compensated_dot3(a, alpha, b, dot3_rounded(a, b));
  const double propagated = std::fabs(o) * D.radius + std::fabs(d) * N.radius;
  return {v.hi, v.lo,
          plus_absolute(raykernel::bounds::affine_propagation_factor * (propagated + v.radius),
                        absolute_constant(raykernel::bounds::affine_absolute))};
}

// The origin of spawn (to_target = false: s = sign(w·N)) or spawn_to (to_target = true: s = σ(q)), when every
// sign and rounding it rests on is certain; nothing otherwise (invalid input included). Runs in the default
// floating-point environment (the caller installs it).
[[nodiscard]] std::optional<SpawnedOrigin> spawn_certified(const HitPoint& hit, const Triangle& source,
                                                           bool to_target, const Vec3& w_or_q, OriginFormat format);

}  // namespace raykernel::detail
