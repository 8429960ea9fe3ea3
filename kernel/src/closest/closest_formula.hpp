// The closest point of a triangle to a point, over any number type (docs/contract.md §11): binary64 for the
// baseline, intervals (core/interval.hpp) for the filter, exact rationals for the exact stage — one formula.
//
// Ericson's Voronoi-region algorithm (Real-Time Collision Detection, §5.1.5), written on the dot products
//   d1 = ab·ap, d2 = ac·ap, d3 = ab·bp, d4 = ac·bp, d5 = ab·cp, d6 = ac·cp
// and the three 2×2 minors vc = d1·d4 − d3·d2, vb = d5·d2 − d1·d6, va = d3·d6 − d5·d4 (which sum to |ab × ac|²).
// Each region is decided by signs of these polynomials, in Ericson's order; its closest point is
//   q = a + (num_v·ab + num_w·ac) / den,   den > 0,
// so that |p − q|² = |den·ap − num_v·ab − num_w·ac|² / den². In exact arithmetic the regions are right for every
// non-degenerate triangle (|ab × ac|² > 0: each edge has positive length, so the edge denominators are too); a
// degenerate triangle — its vertices on a line or one point — is the segment or point it is and is measured
// by the exact stage's segment rule (closest/closest_point.cpp). A vertex region's point is that vertex; an edge
// region's lies strictly inside the edge (Ericson's tests send the edge's ends to the vertex regions).
//
// `sign` returns −1, 0 or +1, or interval_uncertain when the number type cannot tell; the region is then
// `uncertain` and the caller decides in rationals.
#pragma once

#include "core/interval.hpp"

#include <cstdint>

namespace raykernel::detail {

enum class ClosestRegion : std::uint8_t { vertex_a, vertex_b, vertex_c, edge_ab, edge_bc, edge_ca, face, uncertain };

template <class T>
struct Vec3Of {
  T x, y, z;
};
template <class T>
[[nodiscard]] inline Vec3Of<T> operator-(const Vec3Of<T>& u, const Vec3Of<T>& v) {
  return {u.x - v.x, u.y - v.y, u.z - v.z};
}
template <class T>
[[nodiscard]] inline T dot(const Vec3Of<T>& u, const Vec3Of<T>& v) {
  return u.x * v.x + u.y * v.y + u.z * v.z;
}

// The region and the closest point's numerators and denominator over a, ab, ac.
template <class T>
struct ClosestTerms {
  ClosestRegion region = ClosestRegion::uncertain;
  T num_v{}, num_w{}, den{};
};

// A three-valued truth (no, yes, cannot tell) for the region tests.
enum class Truth : std::uint8_t { no, yes, unknown };
[[nodiscard]] inline Truth truth_of(int sign, bool want_nonpositive) noexcept {
  if (sign == interval_uncertain) return Truth::unknown;
  return (want_nonpositive ? sign <= 0 : sign >= 0) ? Truth::yes : Truth::no;
}
[[nodiscard]] inline Truth all_of(Truth a, Truth b, Truth c = Truth::yes) noexcept {
  if (a == Truth::no || b == Truth::no || c == Truth::no) return Truth::no;
  if (a == Truth::yes && b == Truth::yes && c == Truth::yes) return Truth::yes;
  return Truth::unknown;
}

// The terms for p and the triangle (a, b, c), which the caller knows to be non-degenerate. `one` and `zero` are
// the number type's 1 and 0.
template <class T, class Sign>
[[nodiscard]] ClosestTerms<T> closest_terms(const Vec3Of<T>& p, const Vec3Of<T>& a, const Vec3Of<T>& b,
                                            const Vec3Of<T>& c, const T& zero, const T& one, Sign sign) {
  const auto le0 = [&](const T& x) { return truth_of(sign(x), true); };
  const auto ge0 = [&](const T& x) { return truth_of(sign(x), false); };
  ClosestTerms<T> r;
  const auto decide = [&](Truth t, ClosestRegion region, const T& v, const T& w, const T& den) {
    if (t == Truth::yes) r = {region, v, w, den};
    return t;  // the caller goes on only on no
  };
  const Vec3Of<T> ab = b - a, ac = c - a, ap = p - a;
  const T d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (decide(all_of(le0(d1), le0(d2)), ClosestRegion::vertex_a, zero, zero, one) != Truth::no) return r;
  const Vec3Of<T> bp = p - b;
  const T d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (decide(all_of(ge0(d3), le0(d4 - d3)), ClosestRegion::vertex_b, one, zero, one) != Truth::no) return r;
  const T vc = d1 * d4 - d3 * d2;
  if (decide(all_of(le0(vc), ge0(d1), le0(d3)), ClosestRegion::edge_ab, d1, zero, d1 - d3) != Truth::no) return r;
  const Vec3Of<T> cp = p - c;
  const T d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (decide(all_of(ge0(d6), le0(d5 - d6)), ClosestRegion::vertex_c, zero, one, one) != Truth::no) return r;
  const T vb = d5 * d2 - d1 * d6;
  if (decide(all_of(le0(vb), ge0(d2), le0(d6)), ClosestRegion::edge_ca, zero, d2, d2 - d6) != Truth::no) return r;
  const T va = d3 * d6 - d5 * d4;
  const T e = d4 - d3, f = d5 - d6;  // w = e/(e + f) along bc: v = f/(e + f)
  if (decide(all_of(le0(va), ge0(e), ge0(f)), ClosestRegion::edge_bc, f, e, e + f) != Truth::no) return r;
  r = {ClosestRegion::face, vb, vc, va + vb + vc};
  return r;
}

// den·ap − num_v·ab − num_w·ac: den times the vector from the closest point to p.
template <class T>
[[nodiscard]] Vec3Of<T> scaled_offset(const ClosestTerms<T>& t, const Vec3Of<T>& p, const Vec3Of<T>& a,
                                      const Vec3Of<T>& b, const Vec3Of<T>& c) {
  const Vec3Of<T> ab = b - a, ac = c - a, ap = p - a;
  return {t.den * ap.x - t.num_v * ab.x - t.num_w * ac.x, t.den * ap.y - t.num_v * ab.y - t.num_w * ac.y,
          t.den * ap.z - t.num_v * ab.z - t.num_w * ac.z};
}

}  // namespace raykernel::detail
