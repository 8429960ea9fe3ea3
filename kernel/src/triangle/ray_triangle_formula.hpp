// The ray–triangle formulas of docs/contract.md §6, written once and evaluated in every number type: double
// (the naive values), GMP rationals (the exact reference), the certified stages' types (the binary64 filter's
// value-and-magnitude pairs, the compensated stage's double-doubles, exact expansions). Each stage follows
// these templates operation by operation, so the proofs (proofs/Triangle*.v) model one evaluation order.
//
// With e_v = v − o for v ∈ {a, b, c} and the cross products
//
//     c_a = e_b × e_c,   c_b = e_c × e_a,   c_c = e_a × e_b,
//
// the three edge values are πa = d·c_a = π(b, c), πb = d·c_b = π(c, a), πc = d·c_c = π(a, b), and
//
//     den = (πa + πb) + πc  = d·((b − a) × (c − a))      (the cross products sum to (b − a) × (c − a))
//     num = e_a·c_a = det(e_a, e_b, e_c) = (a − o)·((b − a) × (c − a)).
//
// Each is a degree-3 polynomial in the input doubles (a 3×3 determinant, as Shewchuk's orient3d): d and the
// differences e_v enter once each per product. The degree-2 values: N = (b − a) × (c − a) (the triangle is
// degenerate iff N = 0) and the owned rule's tie-break vectors d × (q − p).
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <utility>

namespace raykernel::detail {

// The five degree-3 values of one query, in a number type P (the type of a sum of products; D that of a sum
// of three, which differs for expansions, whose capacity grows).
template <class P, class D = P>
struct RayTriangleTerms {
  std::array<P, 3> pi;  // πa, πb, πc
  D den;                // (πa + πb) + πc
  P num;                // e_a·c_a
};

// The cross product y × z, component by component: (y_1 z_2 − y_2 z_1, y_2 z_0 − y_0 z_2, y_0 z_1 − y_1 z_0).
// (Always inlined: the certified stages instantiate these inside multiversioned functions, whose FMA clone
// must see every operation.)
template <class Leaf>
[[nodiscard]] [[gnu::always_inline]] inline auto cross_terms(const std::array<Leaf, 3>& y, const std::array<Leaf, 3>& z) {
  using P = decltype(y[1] * z[2] - y[2] * z[1]);
  return std::array<P, 3>{y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2], y[0] * z[1] - y[1] * z[0]};
}

// x·c = (x_0 c_0 + x_1 c_1) + x_2 c_2.
template <class Leaf, class P>
[[nodiscard]] [[gnu::always_inline]] inline auto dot_terms(const std::array<Leaf, 3>& x, const std::array<P, 3>& c) {
  return (x[0] * c[0] + x[1] * c[1]) + x[2] * c[2];
}

// The inputs as the formulas consume them: `lift` maps an input double to a Leaf (exactly, for an exact type);
// `difference(v, w)` gives the Leaf of v − w (rounded once in binary64 for the filter, exact as a double-double
// for the compensated stage and the expansions, exact for rationals).
template <class Leaf>
struct RayTriangleLeaves {
  std::array<Leaf, 3> d;
  std::array<std::array<Leaf, 3>, 3> e;  // e_a, e_b, e_c
};

template <class Leaf, class Lift, class Difference>
[[nodiscard]] [[gnu::always_inline]] inline RayTriangleLeaves<Leaf> ray_triangle_leaves(const Ray& ray, const Triangle& triangle, Lift lift,
                                                          Difference difference) {
  const Vec3& o = ray.origin;
  const Vec3& d = ray.direction;
  auto e = [&](const Vec3& v) {
    return std::array<Leaf, 3>{difference(v.x, o.x), difference(v.y, o.y), difference(v.z, o.z)};
  };
  return {{lift(d.x), lift(d.y), lift(d.z)}, {e(triangle.a), e(triangle.b), e(triangle.c)}};
}

// The five values from the leaves: the cross products are shared (c_a by πa and num).
template <class Leaf>
[[nodiscard]] [[gnu::always_inline]] inline auto ray_triangle_terms(const RayTriangleLeaves<Leaf>& in) {
  const auto& [ea, eb, ec] = in.e;
  const auto ca = cross_terms(eb, ec);
  const auto cb = cross_terms(ec, ea);
  const auto cc = cross_terms(ea, eb);
  using P = std::decay_t<decltype(dot_terms(in.d, ca))>;
  const std::array<P, 3> pi{dot_terms(in.d, ca), dot_terms(in.d, cb), dot_terms(in.d, cc)};
  auto den = (pi[0] + pi[1]) + pi[2];
  return RayTriangleTerms<P, decltype(den)>{pi, std::move(den), dot_terms(ea, ca)};
}

template <class Leaf, class Lift, class Difference>
[[nodiscard]] auto ray_triangle_terms(const Ray& ray, const Triangle& triangle, Lift lift, Difference difference) {
  return ray_triangle_terms(ray_triangle_leaves<Leaf>(ray, triangle, lift, difference));
}

// The vector q − p as leaves, each component one difference of doubles (exact for an exact Leaf): an edge of a
// triangle, or the exact direction of the segment from p to q (docs/contract.md §8, which is not rounded).
template <class Leaf, class Difference>
[[nodiscard]] [[gnu::always_inline]] inline std::array<Leaf, 3> difference_leaves(const Vec3& p, const Vec3& q,
                                                                                  Difference difference) {
  return {difference(q.x, p.x), difference(q.y, p.y), difference(q.z, p.z)};
}

// The owned rule's tie-break vector d × (q − p) of the directed edge p → q, for a direction given as leaves: the
// ray's d lifted (triangle_tie_breaks), or a segment's exact q − p as differences (occlusion/segment_triangle.hpp).
// Each component is a degree-2 polynomial in the doubles: d_i (q_j − p_j) − d_j (q_i − p_i).
template <class Leaf, class Difference>
[[nodiscard]] auto edge_tie_break(const std::array<Leaf, 3>& d, const Vec3& p, const Vec3& q, Difference difference) {
  return cross_terms(d, difference_leaves<Leaf>(p, q, difference));
}

// The degree-2 values: the tie-break vector d × (q − p) of each directed edge p → q (b → c for πa, c → a
// for πb, a → b for πc), and N = (b − a) × (c − a).
template <class Leaf, class Lift, class Difference>
[[nodiscard]] auto triangle_tie_breaks(const Ray& ray, const Triangle& triangle, Lift lift, Difference difference) {
  const std::array<Leaf, 3> d{lift(ray.direction.x), lift(ray.direction.y), lift(ray.direction.z)};
  const Vec3 &a = triangle.a, &b = triangle.b, &c = triangle.c;
  using C = decltype(cross_terms(d, d));
  return std::array<C, 3>{edge_tie_break(d, b, c, difference), edge_tie_break(d, c, a, difference),
                          edge_tie_break(d, a, b, difference)};
}

template <class Leaf, class Difference>
[[nodiscard]] auto triangle_normal(const Triangle& triangle, Difference difference) {
  const Vec3 &a = triangle.a, &b = triangle.b, &c = triangle.c;
  const std::array<Leaf, 3> ab{difference(b.x, a.x), difference(b.y, a.y), difference(b.z, a.z)};
  const std::array<Leaf, 3> ac{difference(c.x, a.x), difference(c.y, a.y), difference(c.z, a.z)};
  return cross_terms(ab, ac);
}

// ---------------------------------------------------------------------------------------------------------
// The decisions of docs/contract.md §6 from exact signs (−1, 0, +1). No arithmetic: shared by every path.

// The location from the signs of πa, πb, πc and den (den ≠ 0).
[[nodiscard]] constexpr TriangleLocation triangle_location(int sa, int sb, int sc, int sden) noexcept {
  if (sa == -sden || sb == -sden || sc == -sden) return TriangleLocation::outside;  // (sden ≠ 0)
  if (sb == 0 && sc == 0) return TriangleLocation::vertex_a;
  if (sc == 0 && sa == 0) return TriangleLocation::vertex_b;
  if (sa == 0 && sb == 0) return TriangleLocation::vertex_c;
  if (sc == 0) return TriangleLocation::edge_ab;
  if (sa == 0) return TriangleLocation::edge_bc;
  if (sb == 0) return TriangleLocation::edge_ca;
  return TriangleLocation::inside;
}

// The owned rule's sign of one π: its own sign, or when it is 0, the sign of the first nonzero of the x, y, z
// components of its tie-break vector d × (q − p) (given as signs). Never 0 when den ≠ 0
// (proofs/triangle/TriangleRule.v, `owned_sign_nonzero`).
[[nodiscard]] constexpr int owned_sign(int pi_sign, int tx, int ty, int tz) noexcept {
  if (pi_sign != 0) return pi_sign;
  return tx != 0 ? tx : (ty != 0 ? ty : tz);
}

// The relation under a rule, for den ≠ 0: `through` is whether the rule lets the line through (closed: the
// location is not outside; owned: all three owned signs equal den's), and t ≥ 0 iff num·den ≥ 0.
[[nodiscard]] constexpr TriangleRelation crossing_relation(bool through, int snum, int sden) noexcept {
  if (!through) return TriangleRelation::miss;
  return snum * sden >= 0 ? TriangleRelation::hit : TriangleRelation::behind;
}

// The relation when den = 0: degenerate (N = 0), else parallel or coplanar by num.
[[nodiscard]] constexpr TriangleRelation non_crossing_relation(bool normal_is_zero, int snum) noexcept {
  if (normal_is_zero) return TriangleRelation::degenerate;
  return snum == 0 ? TriangleRelation::coplanar : TriangleRelation::parallel;
}

// The whole classification from exact signs, asking only for what the answer depends on: `den_sign()` and
// `pi_sign(k)` always (k = 0, 1, 2 for πa, πb, πc); `tie_break_signs(k)` (the signs of the x, y, z components
// of the tie-break vector) only for a π that is 0, under the owned rule, when den ≠ 0; `num_sign()` only for a
// line through the triangle (den ≠ 0) or when den = 0 and N ≠ 0; `normal_is_zero()` only when den = 0.
template <class DenSign, class PiSign, class TieBreakSigns, class NumSign, class NormalIsZero>
[[nodiscard]] TriangleClassification classify_triangle(TriangleRule rule, DenSign den_sign, PiSign pi_sign,
                                                       TieBreakSigns tie_break_signs, NumSign num_sign,
                                                       NormalIsZero normal_is_zero) {
  const int sden = den_sign();
  if (sden == 0) {
    const bool degenerate = normal_is_zero();
    return {non_crossing_relation(degenerate, degenerate ? 0 : num_sign()), TriangleLocation::none, false};
  }
  const int s[3] = {pi_sign(0), pi_sign(1), pi_sign(2)};
  const TriangleLocation location = triangle_location(s[0], s[1], s[2], sden);
  bool owned = location != TriangleLocation::outside;  // a π opposite to den stays opposite under the rule
  for (int k = 0; k < 3 && owned; ++k) {
    if (s[k] != 0) continue;
    const std::array<int, 3> tie = tie_break_signs(k);
    owned = owned_sign(0, tie[0], tie[1], tie[2]) == sden;
  }
  const bool through = rule == TriangleRule::owned ? owned : location != TriangleLocation::outside;
  return {through ? crossing_relation(true, num_sign(), sden) : TriangleRelation::miss, location, owned};
}

}  // namespace raykernel::detail
