// The planar orientation sign the point-in-mesh query decides its crossings with, certified: a binary64 filter,
// then exact rationals (mesh/exact_mesh.hpp) when the filter cannot decide; and the 3D orientation of its
// on-surface test (filter, exact expansions, rationals), with the on-triangle test for a coplanar point.
//
// For a ray along an axis, d = s·e_k (s = ±1), every value of docs/contract.md §6 that decides a crossing is a
// 2×2 determinant in the plane of the other two axes (i, j) = ((k + 1) mod 3, (k + 2) mod 3):
//
//     π(p, q) = d·((p − o) × (q − o)) = s·orient2d(p, q, o),    den = d·N = s·orient2d(b, c, a),
//
// with orient2d(p, q, r) = (p_i − r_i)(q_j − r_j) − (p_j − r_j)(q_i − r_i) (Shewchuk's orientation of three
// points; positive when p, q, r turn counterclockwise in the (i, j) plane). The owned rule's tie-break vectors
// d × (q − p) have components ±(q_m − p_m), whose signs are comparisons of doubles.
#pragma once

#include "core/absolute_terms.hpp"
#include "core/escalation.hpp"
#include "core/fp_requirements.hpp"
#include "core/sign.hpp"
#include "mesh/exact_mesh.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <raykernel/raykernel.hpp>

#include <cmath>

namespace raykernel::bounds {

// ---------------------------------------------------------------------------------------------------------
// orient2d_filter — the sign of orient2d(p, q, r) from binary64
//
// Formula: x1 = p_i ⊖ r_i, y2 = q_j ⊖ r_j, y1 = p_j ⊖ r_j, x2 = q_i ⊖ r_i, L = x1 ⊗ y2, R = y1 ⊗ x2,
//          D = L ⊖ R, B = (A ⊗ (|L| ⊕ |R|)) ⊕ U;  D > B ⇒ positive, D < −B ⇒ negative, else uncertain.
// Error bound: whenever |D| > B, D has the sign of orient2d; A = 2^-51 (= 4u), U = 2^-1071 (= 16η), u = 2^-53,
//   η = 2^-1075 (half the smallest subnormal).
// Derivation: let X1, Y2, Y1, X2 be the exact differences, P = X1·Y2, Q = Y1·X2, O = P − Q = orient2d. A rounded
//   difference is X(1 + δ), |δ| ≤ u (exact when subnormal); a rounded product is x·y(1 + δ) + e, |e| ≤ η (e = 0
//   unless it is below 2^-1022). So L = P(1 + θ1) + e1 and R = Q(1 + θ2) + e2 with |θ| ≤ θ* = (1 + u)^3 − 1,
//   and |(L − R) − O| ≤ θ*(|P| + |Q|) + 2η ≤ (θ*·S + 2η)/(1 − θ*) with S = |L| + |R| (as |P| ≤ (|L| + η)/(1 − θ*)).
//   D = RN(L − R) has the sign of L − R (RN is monotone and odd) and |D| ≤ (1 + u)|L − R|. The computed B is at
//   least A·S(1 − u)^3 + (U − η)(1 − u)^2 (three roundings, one absolute error η). So |D| > B gives
//   |L − R| > B/(1 + u) > |(L − R) − O| as soon as A(1 − u)^3/(1 + u) ≥ θ*/(1 − θ*) (4u(1 − 4u) against
//   3u + 7u²) and (U − η)(1 − u)^2/(1 + u) ≥ 2η/(1 − θ*) (15η(1 − 3u) against 2.01η): then L − R, hence D, has
//   O's sign. (Shewchuk's orient2d filter, 1997 §4.3, uses (3 + 16u)u and no absolute term: it assumes no
//   underflow and one rounding fewer in B.)
// Valid range: every finite input. An overflow makes D, S or B infinite or NaN, every comparison above is then
//   false or needs D = ±inf > B = inf, so the filter answers uncertain and the exact stage decides.
// Certified by: proofs/orient/OrientFilter.v, `orient2d_filter_sound` (the model: every double; the error
//   bound `orient2d_error`, 3u + 9u² and 4η); for every bit pattern, non-finite inputs and overflow included:
//   proofs/orient/OrientTwins.v, `orient2d_filter_twin_sound` (the twin the runner's group orient checks).
inline constexpr double orient2d_filter_relative = 0x1p-51;
inline constexpr double orient2d_filter_absolute = 0x1p-1071;

// ---------------------------------------------------------------------------------------------------------
// orient3d_filter — the sign of det(a − o, b − o, c − o) from binary64
//
// Formula: the differences ad = a ⊖ o, bd = b ⊖ o, cd = c ⊖ o; D = ad_z ⊗ (bd_x ⊗ cd_y ⊖ cd_x ⊗ bd_y) ⊕
//          bd_z ⊗ (cd_x ⊗ ad_y ⊖ ad_x ⊗ cd_y) ⊕ cd_z ⊗ (ad_x ⊗ bd_y ⊖ bd_x ⊗ ad_y) (Shewchuk's orient3d, in his
//          order); P = (|bd_x ⊗ cd_y| ⊕ |cd_x ⊗ bd_y|) ⊗ |ad_z| ⊕ (|cd_x ⊗ ad_y| ⊕ |ad_x ⊗ cd_y|) ⊗ |bd_z| ⊕
//          (|ad_x ⊗ bd_y| ⊕ |bd_x ⊗ ad_y|) ⊗ |cd_z|;  D > A ⊗ P ⇒ positive, D < −(A ⊗ P) ⇒ negative, else uncertain.
// Error bound: A = 2^-49. Shewchuk (1997, §4.3, o3derrboundA) shows |D − det| ≤ (7u + 56u²)·P for the computed
//   D and P, u = 2^-53, the differences' roundings included, when no operation underflows or overflows; A ⊗ P is
//   at least (7u + 56u²)P since A ≥ 2(7u + 56u²)/(1 − u) (one more rounding).
// Valid range: each difference is 0 or has magnitude in [2^-300, 2^300] (checked; else uncertain): then every
//   nonzero product of two is in [2^-600, 2^600]; a difference of two such products is 0 or at least 2^-652
//   (both are multiples of 2^-652), so every nonzero product the filter rounds is at least 2^-952, and every
//   value stays below 2^905: nothing underflows or overflows and Shewchuk's assumption holds. (A zero difference
//   makes its products exact zeros. A difference of two doubles is rounded only when it is above the subnormal
//   range.)
// Certified by: proofs/orient/OrientFilter.v, `orient3d_filter_sound` (the model: every double; the error bound
//   `orient3d_error`, |D − det| ≤ A ⊗ P in range: about 10u·P against A = 16u); for every bit pattern:
//   proofs/orient/OrientTwins.v, `orient3d_filter_twin_sound` (the twin the runner's group orient checks).
inline constexpr double orient3d_filter_relative = 0x1p-49;
inline constexpr double orient3d_filter_min_difference = 0x1p-300;
inline constexpr double orient3d_filter_max_difference = 0x1p300;

}  // namespace raykernel::bounds

namespace raykernel::mesh_detail {

[[nodiscard]] inline double coordinate(const Vec3& v, int axis) noexcept {
  return axis == 0 ? v.x : (axis == 1 ? v.y : v.z);
}

// orient2d_filter (above): +1, −1, or 0 when uncertain (the filter never certifies a zero).
[[nodiscard]] inline int orient2d_filter(const Vec3& p, const Vec3& q, const Vec3& r, int i, int j) noexcept {
  const double x1 = coordinate(p, i) - coordinate(r, i), y2 = coordinate(q, j) - coordinate(r, j);
  const double y1 = coordinate(p, j) - coordinate(r, j), x2 = coordinate(q, i) - coordinate(r, i);
  const double left = x1 * y2, right = y1 * x2;
  const double det = left - right;
  const double bound = detail::plus_absolute(bounds::orient2d_filter_relative * (std::fabs(left) + std::fabs(right)),
                                             detail::absolute_constant(bounds::orient2d_filter_absolute));
  return (det > bound) - (det < -bound);
}

// orient3d_filter (above): the sign of det(a − o, b − o, c − o), or 0 when uncertain (never a certified zero).
[[nodiscard]] inline int orient3d_filter(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  const double adx = a.x - o.x, ady = a.y - o.y, adz = a.z - o.z;
  const double bdx = b.x - o.x, bdy = b.y - o.y, bdz = b.z - o.z;
  const double cdx = c.x - o.x, cdy = c.y - o.y, cdz = c.z - o.z;
  bool in_range = true;
  for (const double v : {adx, ady, adz, bdx, bdy, bdz, cdx, cdy, cdz}) {
    const double m = std::fabs(v);
    in_range &= m == 0 || (m >= bounds::orient3d_filter_min_difference && m <= bounds::orient3d_filter_max_difference);
  }
  if (!in_range) return 0;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * std::fabs(adz) +
                           (std::fabs(cdxady) + std::fabs(adxcdy)) * std::fabs(bdz) +
                           (std::fabs(adxbdy) + std::fabs(bdxady)) * std::fabs(cdz);
  const double bound = bounds::orient3d_filter_relative * permanent;
  return (det > bound) - (det < -bound);
}

// The exact sign of det(a − o, b − o, c − o): the filter, then exact expansions — the determinant is the ray–triangle
// cascade's num for a ray from o (ray_triangle_stages.hpp's num_expansion; proofs/triangle/TriangleStage3Twins.v,
// `value_ev_exact` and `triangle_expansion_sign_sound`: an exact expansion's checked sign is the exact sign) —
// then rationals when an expansion is not exact (an underflow) or its sign is not certain. The expansions
// decide the exact zeros a point in a triangle's plane gives (inside() on flat meshes) at a fraction of the
// rationals' cost.
[[nodiscard]] inline int orient3d_sign(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  return detail::Escalation{}.exact_sign(
      [&] { return detail::exact::det3_sign(o, a, b, c); },
      detail::SignStage{Stage::filter, [&] { return detail::sign_or_uncertain(orient3d_filter(o, a, b, c)); }},
      detail::SignStage{Stage::expansion,
                        [&] { return detail::num_expansion(Ray{o, {0, 0, 0}}, Triangle{a, b, c}).sign(); }});
}

// The exact sign of orient2d(p, q, r) in the plane of axes (i, j).
[[nodiscard]] inline int orient2d_sign(const Vec3& p, const Vec3& q, const Vec3& r, int i, int j) {
  // Both products have an exactly zero factor — a triangle parallel to the ray's axis, a point sharing a
  // coordinate with two vertices: orient2d is exactly 0, which the filter cannot certify. (A difference of two
  // doubles is 0 exactly when they are equal, gradual underflow included.)
  const bool left_zero = coordinate(p, i) == coordinate(r, i) || coordinate(q, j) == coordinate(r, j);
  const bool right_zero = coordinate(p, j) == coordinate(r, j) || coordinate(q, i) == coordinate(r, i);
  if (left_zero && right_zero) return 0;
  return detail::Escalation{}.exact_sign(
      [&] { return detail::exact::orient2d_sign(p, q, r, i, j); },
      detail::SignStage{Stage::filter, [&] { return detail::sign_or_uncertain(orient2d_filter(p, q, r, i, j)); }});
}

// Whether p, coplanar with the triangle (det(a − p, b − p, c − p) = 0 exactly), lies on the closed triangle:
// exact::point_on_triangle's decision after its coplanarity test, step for step, with the filtered orientations
// (orient2d_sign: the filter, then rationals) — the same exact signs, so the same answer.
[[nodiscard]] inline bool coplanar_point_on_triangle(const Vec3& p, const Triangle& t) {
  // N_k = ((b − a) × (c − a))_k is orient2d(b, c, a) in the plane of axes (k + 1, k + 2) mod 3; a projection
  // along an axis with N_k ≠ 0 maps the plane one to one, keeping the orientation n.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int n = orient2d_sign(t.b, t.c, t.a, i, j);
    if (n == 0) continue;
    return orient2d_sign(t.a, t.b, p, i, j) != -n && orient2d_sign(t.b, t.c, p, i, j) != -n &&
           orient2d_sign(t.c, t.a, p, i, j) != -n;
  }
  // Degenerate (N = 0): on one of the three edges [u, v]: (v − u) × (p − u) = 0 and p within their box.
  auto within = [](double x, double a, double b) { return (a <= x && x <= b) || (b <= x && x <= a); };
  const Vec3* edges[3][2] = {{&t.a, &t.b}, {&t.b, &t.c}, {&t.c, &t.a}};
  for (const auto& e : edges) {
    const Vec3 &u = *e[0], &v = *e[1];
    bool on = true;
    for (int k = 0; k < 3 && on; ++k)
      on = orient2d_sign(u, v, p, (k + 1) % 3, (k + 2) % 3) == 0 && within(coordinate(p, k), coordinate(u, k), coordinate(v, k));
    if (on) return true;
  }
  return false;
}

}  // namespace raykernel::mesh_detail
