// Stage 1 of a root's rounding in the ray–sphere cascade: the signs of q(m) = A·m² + 2B·m + C and of the slope
// A·m + B at a rounding boundary m = (x + y)/2, in double-double binary64 with a semi-static error bound, so that
// a root's correct rounding is decided without expansions (docs/contract.md §10; the formula:
// ray_sphere_formula.hpp; the walk over boundaries: core/quotient_boundary.hpp, round_walking_to_midpoints).
//
// With M = x + y = M₁ + M₂ (TwoSum, exact) and f = o − c: 4q(m) = Σ_i G_i² − (2r)², G_i = 2f_i + M·d_i = 2g_i,
// and 2(A·m + B) = Σ_i d_i·G_i. Per axis, the parts of G_i are exact or nearly: (f̂, f̌) = TwoDiff(o_i, c_i),
// P = M₁ ⊗ d_i and π = fma(M₁, d_i, −P) (M₁·d_i = P + π unless it underflows), Q = M₂ ⊗ d_i; then
// (H, h) = TwoSum(2f̂, P) and L = (h ⊕ 2f̌) ⊕ (π ⊕ Q), so that G_i = H + L up to ~u²·T, T = 2|f̂| + |P| (the
// magnitude before the cancellation of 2f and M·d near a root). 4q = Σ H² + Σ L·(2H + L) − (2r)²: each H² and
// (2r)² as TwoProduct, their heads summed by TwoSum (the cancellation happens there, exactly), and the small rest
// in plain binary64.
//   Error bound: |4q(m) − (â ⊕ s)| ≤ E_q = (κ_q ⊗ W) ⊕ μ_q with W = Σ_i T_i ⊗ (|H_i| ⊕ 2^-45 ⊗ T_i) ⊕ ΣS_i ⊕ R
//   (core/error_bounds.hpp, "Ray–sphere roots", for the derivation); the slope's from Σ d_i·H_i, |L_i| ≤ 3.1u·T_i:
//   E_s = (κ_s ⊗ Σ |d_i| ⊗ ((|H_i| ⊕ T_i) ⊕ 2^-1000)) ⊕ μ_s.
//   Valid range: all finite inputs; uncertain (never wrong) when anything overflows (W, or the value, not finite).
//   Certified by: proofs/sphere/SphereBoundaryFilter.v, `sphere_boundary_q_sound` and
//   `sphere_boundary_slope_sound` (proved for every binary64 input; also tested: certified == exact on every hard
//   sphere kind, 10^6 cases in sphere_properties_1M, and fuzz_sphere).
#pragma once

#include "core/absolute_terms.hpp"
#include "core/eft.hpp"
#include "core/error_bounds.hpp"
#include "core/sign.hpp"
#include "sphere/ray_sphere_formula.hpp"

#include <raykernel/sphere.hpp>

#include <cmath>
#include <type_traits>

namespace raykernel::detail {

struct SphereBoundarySigns {
  Sign q, slope;  // sign(q(m)), and sign(A·m + B) when q(m) > 0; or uncertain
  double q4, slope2;  // ≈ 4q(m) and ≈ 2(A·m + B): a Newton step's candidate, never a decision
  double q4_bound;    // E_q: |4q(m) − q4| ≤ E_q when it is finite (tests check the margin)
};

// The filter written once over V = double or Lanes4 (four boundaries at once: each lane performs exactly the
// scalar operations, so each lane's signs are the scalar filter's; core/lanes.hpp), the signs as integer lanes.
template <class V>
struct SphereBoundaryLanes {
  IntegerOf<V> q, slope;
  V q4, slope2, q4_bound;
};

// Each lane the double x, bit for bit (V{} + x would turn a −0 into +0).
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V splat(double x) noexcept {
  if constexpr (std::is_same_v<V, double>) {
    return x;
  } else {
    V r;
    for (int i = 0; i < width_of<V>; ++i) r[i] = x;
    return r;
  }
}

template <class V>
[[nodiscard]] [[gnu::always_inline]] inline SphereBoundaryLanes<V> sphere_boundary_filter_lanes(const Ray& ray,
                                                                                                const Sphere& sphere,
                                                                                                V x, V y) noexcept {
  const V o[3] = {splat<V>(ray.origin.x), splat<V>(ray.origin.y), splat<V>(ray.origin.z)};
  const V d[3] = {splat<V>(ray.direction.x), splat<V>(ray.direction.y), splat<V>(ray.direction.z)};
  const V c[3] = {splat<V>(sphere.center.x), splat<V>(sphere.center.y), splat<V>(sphere.center.z)};
  const DD<V> m = two_sum(x, y);  // M = x + y, exactly
  V h_head[3], low[3], t[3];
  for (int i = 0; i < 3; ++i) {
    const DD<V> f = two_diff(o[i], c[i]);  // o_i − c_i, exactly
    const V p = m.hi * d[i];
    const V pi = fma(m.hi, d[i], -p);  // M₁·d_i − P, exactly unless it underflows
    const V q = m.lo * d[i];
    const DD<V> head = two_sum(f.hi + f.hi, p);  // 2f̂ exact (a power of two)
    h_head[i] = head.hi;
    low[i] = (head.lo + (f.lo + f.lo)) + (pi + q);
    t[i] = (abs(f.hi) + abs(f.hi)) + abs(p);
  }
  const V radius = splat<V>(sphere.radius);
  const V two_r = radius + radius;
  const DD<V> s0 = two_prod(h_head[0], h_head[0]), s1 = two_prod(h_head[1], h_head[1]),
              s2 = two_prod(h_head[2], h_head[2]), rr = two_prod(two_r, two_r);
  const DD<V> a1 = two_sum(s0.hi, s1.hi), a2 = two_sum(a1.hi, s2.hi), a3 = two_sum(a2.hi, -rr.hi);
  V k[3];
  for (int i = 0; i < 3; ++i) k[i] = low[i] * ((h_head[i] + h_head[i]) + low[i]);  // L·(2H + L)
  const V small = (((s0.lo + s1.lo) + (s2.lo - rr.lo)) + ((a1.lo + a2.lo) + a3.lo)) + ((k[0] + k[1]) + k[2]);
  const V value = a3.hi + small;
  V w = ((s0.hi + s1.hi) + s2.hi) + rr.hi;
  for (int i = 0; i < 3; ++i) w += t[i] * (abs(h_head[i]) + bounds::sphere_boundary_tail * t[i]);
  const V slope = (d[0] * h_head[0] + d[1] * h_head[1]) + d[2] * h_head[2];  // 2(A·m + B) = Σ d_i·G_i
  const V e_q =
      plus_absolute(bounds::sphere_boundary_q_relative * w, absolute_constant(bounds::sphere_boundary_q_absolute));
  // Certain only where W and the value are finite (no comparison holds with a NaN).
  const auto finite = both(w <= bounds::largest_finite, abs(value) <= bounds::largest_finite);
  const IntegerOf<V> uncertain = IntegerOf<V>{} + uncertain_lane;
  const IntegerOf<V> q_sign = select(finite, sign_lanes(value > e_q, value < -e_q), uncertain);
  // The slope's sign, from the heads alone: read by root_side_of only when q(m) > 0, so certified only then.
  V slope_magnitude{};  // from 0, as the proof's model sums it
  for (int i = 0; i < 3; ++i)
    slope_magnitude += abs(d[i]) * ((abs(h_head[i]) + t[i]) + bounds::sphere_boundary_slope_floor);
  const V e_s = plus_absolute(bounds::sphere_boundary_slope_relative * slope_magnitude,
                              absolute_constant(bounds::sphere_boundary_slope_absolute));
  const auto slope_read = both(q_sign == IntegerOf<V>{} + 1, slope_magnitude <= bounds::largest_finite);
  const IntegerOf<V> slope_sign = select(slope_read, sign_lanes(slope > e_s, slope < -e_s), uncertain);
  return {q_sign, slope_sign, value, slope, e_q};
}

[[nodiscard]] [[gnu::always_inline]] inline SphereBoundarySigns sphere_boundary_filter(const Ray& ray, const Sphere& sphere,
                                                                                       double x, double y) noexcept {
  const SphereBoundaryLanes<double> b = sphere_boundary_filter_lanes<double>(ray, sphere, x, y);
  return {static_cast<Sign>(b.q), static_cast<Sign>(b.slope), b.q4, b.slope2, b.q4_bound};
}

// A root's candidate one Newton step from t: t − q(t)/q'(t) with q(t) and q'(t) from the filter's approximations
// (double-double residual, so a candidate ulps off lands within about an ulp); t itself when the step is not finite.
// Never a decision: the walk over boundaries decides.
// (Per lane for V = Lanes2: both roots' candidates in one pass.)
template <class V>
[[nodiscard]] [[gnu::always_inline]] inline V sphere_root_newton_step(const Ray& ray, const Sphere& sphere, V t) noexcept {
  const SphereBoundaryLanes<V> b = sphere_boundary_filter_lanes<V>(ray, sphere, t, t);  // M = 2t: 4q(t) and 2(A·t + B)
  const V next = t - b.q4 / (b.slope2 * 4);
  return select(abs(next) <= bounds::largest_finite, next, t);  // t itself when the step is not finite
}

// sign(t_k − (x + y)/2) for the root k (−1: t1 or t0, +1: t2 or t0), D ≥ 0, from the filter's signs (root_side_of
// of ray_sphere_formula.hpp: the slope is read only when q(m) > 0); uncertain when a sign it needs is.
[[nodiscard]] [[gnu::always_inline]] inline Sign sphere_root_side_filtered(const Ray& ray, const Sphere& sphere, int root, double x,
                                                    double y) noexcept {
  const SphereBoundarySigns s = sphere_boundary_filter(ray, sphere, x, y);
  if (s.q == Sign::negative) return sign_from_int(root_side_of(root, -1, 0));
  if (s.q != Sign::positive || !is_certain(s.slope)) return Sign::uncertain;
  return sign_from_int(root_side_of(root, 1, static_cast<int>(s.slope)));
}

}  // namespace raykernel::detail
