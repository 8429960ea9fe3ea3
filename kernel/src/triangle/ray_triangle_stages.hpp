// The per-query state of the certified ray–triangle cascade: the leaves, stage 1 or stage 2 values of the five
// determinants (πa, πb, πc, den, num), and stage 3 on demand. Used by the cascade (ray_triangle_cascade.cpp)
// and by the stage tests, which check each stage alone against exact rationals.
#pragma once

#include "core/enclosure.hpp"
#include "core/sign.hpp"
#include "core/error_bounds.hpp"
#include "triangle/ray_triangle_formula.hpp"
#include "core/det3_stages.hpp"
#include "core/expansion_value.hpp"
#include "core/integer_det3.hpp"
#include "core/on_first_use.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <optional>

namespace raykernel::detail {

// Indices of the five determinants.
inline constexpr int value_pi_a = 0, value_pi_b = 1, value_pi_c = 2, value_den = 3, value_num = 4;
inline constexpr int triangle_value_count = 5;

// The relative constant of each determinant's filter and enclosure (error_bounds.hpp).
[[nodiscard]] constexpr double filter_relative(int value) noexcept {
  return value == value_den   ? bounds::triangle_filter_den_relative
         : value == value_num ? bounds::triangle_filter_num_relative
                              : bounds::triangle_filter_pi_relative;
}
[[nodiscard]] constexpr double compensated_relative(int value) noexcept {
  return value == value_den ? bounds::triangle_compensated_den_relative : bounds::triangle_compensated_relative;
}

// Stage 1 of one query: the five values with their permanents, and the two absolute terms (d: π's and den;
// ê_a: num).
struct TriangleFilterValues {
  std::array<FilterTerm<double>, triangle_value_count> value;
  double absolute_d, absolute_e;
  [[nodiscard]] double absolute(int v) const noexcept { return v == value_num ? absolute_e : absolute_d; }
};

// Stage 2 of one query (whose high parts and magnitudes are stage 1's).
struct TriangleCompensatedValues {
  std::array<CompensatedTerm<double>, triangle_value_count> value;
  double absolute_d, absolute_e;
  [[nodiscard]] double absolute(int v) const noexcept { return v == value_num ? absolute_e : absolute_d; }
  [[nodiscard]] TriangleFilterValues filter() const noexcept {
    TriangleFilterValues f{};
    for (int v = 0; v < triangle_value_count; ++v) f.value[static_cast<std::size_t>(v)] = filter_view(value[static_cast<std::size_t>(v)]);
    f.absolute_d = absolute_d;
    f.absolute_e = absolute_e;
    return f;
  }
  [[nodiscard]] Enclosure enclosure(int v) const noexcept {
    return det3_enclosure(value[static_cast<std::size_t>(v)], compensated_relative(v), absolute(v));
  }
};

// Stage 3: the five values as exact expansions (πa, πb, πc, den, num), each usable when `.exact`.
struct TriangleExpansions {
  std::array<ExpansionValue<192>, 3> pi;
  ExpansionValue<192> den;
  ExpansionValue<192> num;
  [[nodiscard]] Sign sign(int v) const noexcept {
    return v == value_den ? den.sign() : v == value_num ? num.sign() : pi[static_cast<std::size_t>(v)].sign();
  }
};

[[nodiscard]] [[gnu::always_inline]] inline TriangleFilterValues triangle_filter_values(const Ray& ray, const Triangle& triangle) noexcept {
  const auto leaves = ray_triangle_leaves<FilterLeaf<double>>(
      ray, triangle, [](double x) { return FilterLeaf<double>{x}; },
      [](double v, double w) { return FilterLeaf<double>{v - w}; });
  const auto t = ray_triangle_terms(leaves);
  const auto& d = leaves.d;
  const auto& ea = leaves.e[0];
  return {{t.pi[0], t.pi[1], t.pi[2], t.den, t.num},
          det3_absolute_term(d[0].v, d[1].v, d[2].v),
          det3_absolute_term(ea[0].v, ea[1].v, ea[2].v)};
}

[[nodiscard]] [[gnu::always_inline]] inline TriangleCompensatedValues triangle_compensated_values(const Ray& ray,
                                                                           const Triangle& triangle) noexcept {
  const auto leaves = ray_triangle_leaves<CompensatedLeaf<double>>(
      ray, triangle, [](double x) { return CompensatedLeaf<double>{x, 0.0}; },
      [](double v, double w) {
        const DoubleDouble s = two_diff(v, w);
        return CompensatedLeaf<double>{s.hi, s.lo};
      });
  const auto t = ray_triangle_terms(leaves);
  const auto& d = leaves.d;
  const auto& ea = leaves.e[0];
  return {{t.pi[0], t.pi[1], t.pi[2], t.den, t.num},
          det3_absolute_term(d[0].h, d[1].h, d[2].h),
          det3_absolute_term(ea[0].h, ea[1].h, ea[2].h)};
}

// Stage 3, one value at a time (the cascade asks only for the values the cheaper stages left open): the
// formula's determinants in expansions. π(p, q) = d·((p − o) × (q − o)); den = π(b, c) seen from a, i.e.
// d·((b − a) × (c − a)) (the same exact value as (πa + πb) + πc, with a shorter expansion); num =
// (a − o)·((b − o) × (c − o)).
//
// Each determinant is x·(y × z) of three of six leaf vectors — d, e_a, e_b, e_c (v − o) and den's b − a, c − a —
// chosen once (determinant_leaves, leaf_vector) and shared by the expansions here and by the integers below.
inline constexpr int leaf_d = 0, leaf_ea = 1, leaf_eb = 2, leaf_ec = 3, leaf_ab = 4, leaf_ac = 5, leaf_count = 6;
// Determinant v's vectors (x, y, z), by leaf: πa = d·(e_b × e_c), πb = d·(e_c × e_a), πc = d·(e_a × e_b),
// den = d·((b − a) × (c − a)), num = e_a·(e_b × e_c).
inline constexpr int determinant_leaves[triangle_value_count][3] = {
    {leaf_d, leaf_eb, leaf_ec}, {leaf_d, leaf_ec, leaf_ea}, {leaf_d, leaf_ea, leaf_eb}, {leaf_d, leaf_ab, leaf_ac},
    {leaf_ea, leaf_eb, leaf_ec}};
// Leaf `leaf` as the difference p − from of two points, or (leaf_d) the direction itself (from null).
struct LeafVector {
  const Vec3 *p, *from;
};
[[nodiscard]] inline LeafVector leaf_vector(const Ray& ray, const Triangle& t, int leaf) noexcept {
  switch (leaf) {
    case leaf_d: return {&ray.direction, nullptr};
    case leaf_ea: return {&t.a, &ray.origin};
    case leaf_eb: return {&t.b, &ray.origin};
    case leaf_ec: return {&t.c, &ray.origin};
    case leaf_ab: return {&t.b, &t.a};
    default: return {&t.c, &t.a};
  }
}

// Leaf `leaf` in expansions: d lifted, a difference exactly (TwoDiff).
[[nodiscard]] inline std::array<ExpansionValue<2>, 3> expansion_leaf(const Ray& ray, const Triangle& t, int leaf) noexcept {
  const LeafVector w = leaf_vector(ray, t, leaf);
  const Vec3& p = *w.p;
  if (w.from == nullptr) return {expansion_of(p.x), expansion_of(p.y), expansion_of(p.z)};
  const Vec3& f = *w.from;
  return {expansion_difference(p.x, f.x), expansion_difference(p.y, f.y), expansion_difference(p.z, f.z)};
}

[[nodiscard]] inline ExpansionValue<192> value_expansion(const Ray& ray, const Triangle& t, int v) noexcept {
  const int* l = determinant_leaves[v];
  return dot_terms(expansion_leaf(ray, t, l[0]), cross_terms(expansion_leaf(ray, t, l[1]), expansion_leaf(ray, t, l[2])));
}
// num = (a − o)·((b − o) × (c − o)) alone (also orient3d's stage 3: orient/orient_predicates.hpp).
[[nodiscard]] inline ExpansionValue<192> num_expansion(const Ray& ray, const Triangle& t) noexcept {
  return value_expansion(ray, t, value_num);
}

// Stage 3's first try for determinant v: its exact sign in integers (core/integer_det3.hpp). Each leaf is read as
// integers over one power of two: d itself, and a difference p − o as TwoDiff's two parts (hi + lo = p − o
// exactly, whether or not p − o is a double: integer_vector_sum). So any leaf whose doubles span fewer than 62 bits
// of exponent and significand — coordinates on a grid, a vertex or an origin a few ulps off — is an integer
// vector; `uncertain` otherwise (the expansions decide then). The leaves are value_expansion's
// (determinant_leaves); IntegerLeaves reads each at most once per query (a ray through a vertex has two zero π
// sharing d and a leaf).
//   Certified by: proofs/triangle/TriangleIntegerSign.v, `integer_value_sign_sound` (its twin integer_value_sign_b,
//   run against this code through the cascade's routines tri_cascade_relation and tri_cascade_intersect).

// Leaf `leaf` as integers over one power of two; not ok when a part is not finite or the integers reach 2^62.
[[nodiscard]] inline IntegerVector integer_leaf(const Ray& ray, const Triangle& t, int leaf) noexcept {
  const LeafVector w = leaf_vector(ray, t, leaf);
  const double pv[3] = {w.p->x, w.p->y, w.p->z};
  if (w.from == nullptr) return integer_vector(pv);
  const double fv[3] = {w.from->x, w.from->y, w.from->z};
  double parts[6];  // h_0, h_1, h_2, l_0, l_1, l_2
  for (int i = 0; i < 3; ++i) {
    const DoubleDouble s = two_diff(pv[i], fv[i]);
    parts[i] = s.hi;
    parts[i + 3] = s.lo;
  }
  return integer_vector_sum(parts);
}

// The six leaf vectors of one query in integers, each read on first use.
class IntegerLeaves {
 public:
  IntegerLeaves(const Ray& ray, const Triangle& triangle) noexcept : ray_(ray), triangle_(triangle) {}
  [[nodiscard]] const IntegerVector& operator[](int leaf) noexcept {
    return vector_.get(static_cast<std::size_t>(leaf), [&] { return integer_leaf(ray_, triangle_, leaf); });
  }

 private:
  const Ray& ray_;
  const Triangle& triangle_;
  OnFirstUse<IntegerVector, leaf_count> vector_;
};

[[nodiscard]] inline Sign integer_value_sign(IntegerLeaves& leaves, int v) noexcept {
  const int* l = determinant_leaves[v];
  return integer_det3_sign(leaves[l[0]], leaves[l[1]], leaves[l[2]]);
}
[[nodiscard]] inline Sign integer_value_sign(const Ray& ray, const Triangle& t, int v) noexcept {
  IntegerLeaves leaves(ray, t);
  return integer_value_sign(leaves, v);
}

// Determinant v as at most four doubles whose exact sum it is (core/integer_det3.hpp, integer_det3_components),
// when its leaves are integer vectors (IntegerLeaves) and its chunks' exponents lie in [−1074, 971]; stage
// 3's value for the roundings, instead of the expansion of doubles (a fifth to a tenth of its cost, and never more
// than four components: round_quotient_near's 16 always hold).
//   Certified by: proofs/triangle/TriangleIntegerSign.v, `integer_value_components_sound` (its twin
//   integer_value_components_b, run against this code through the cascade's routine tri_cascade_intersect).
struct IntegerValue {
  Expansion<4> e;
  bool ok;
};
[[nodiscard]] inline IntegerValue integer_value_components(IntegerLeaves& leaves, int v) noexcept {
  const int* l = determinant_leaves[v];
  IntegerValue r;
  r.ok = integer_det3_components(leaves[l[0]], leaves[l[1]], leaves[l[2]], r.e);
  return r;
}

[[nodiscard]] inline TriangleExpansions triangle_expansions(const Ray& ray, const Triangle& triangle) noexcept {
  return {{value_expansion(ray, triangle, value_pi_a), value_expansion(ray, triangle, value_pi_b),
           value_expansion(ray, triangle, value_pi_c)},
          value_expansion(ray, triangle, value_den),
          value_expansion(ray, triangle, value_num)};
}

// ---- The fast path's layout: four determinants in the four lanes of a Lanes4 -------------------------------
//
// The three π and num share their structure, so one evaluation of the formula's cross_terms and dot_terms on
// Lanes4 (lanes.hpp) gives πa, πb, πc and num in lanes 0..3, lane k using the leaves y = e_b, e_c, e_a, e_b and
// z = e_c, e_a, e_b, e_c and the outer vector x = d, d, d, e_a — each lane performing exactly the scalar
// operations, so the same bits as triangle_compensated_values (tested), the proofs' model of each value, up to
// the sign of zeros: broadcast (V{} + x) turns a −0 of o here, of d in triangle_relation_lanes, into +0 (the
// same real; found by the twin runner, which models it: proofs/README.md, "The twins"). den = (πa + πb) + πc is summed from the lanes in scalar. The relation-only path puts den itself,
// d·((b − a) × (c − a)), in lane 3 instead.
inline constexpr int lane_num = 3;

template <class Term>
struct TriangleLanes {
  Term lanes;       // πa, πb, πc, num (or den)
  Lanes4 absolute;  // the absolute term of each lane's outer vector
};

[[nodiscard]] [[gnu::always_inline]] inline TriangleLanes<CompensatedTerm<Lanes4>> triangle_compensated_lanes(
    const Ray& ray, const Triangle& triangle) noexcept {
  const Vec3 &a = triangle.a, &b = triangle.b, &c = triangle.c, &o = ray.origin, &d = ray.direction;
  const double av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z}, cv[3] = {c.x, c.y, c.z}, ov[3] = {o.x, o.y, o.z};
  const double dv[3] = {d.x, d.y, d.z};
  std::array<CompensatedLeaf<Lanes4>, 3> y, z, x;
  for (std::size_t i = 0; i < 3; ++i) {
    const Lanes4 from = broadcast<Lanes4>(ov[i]);
    const DD<Lanes4> ey = two_diff(Lanes4{bv[i], cv[i], av[i], bv[i]}, from);
    const DD<Lanes4> ez = two_diff(Lanes4{cv[i], av[i], bv[i], cv[i]}, from);
    const DoubleDouble ea = two_diff(av[i], ov[i]);
    y[i] = {ey.hi, ey.lo};
    z[i] = {ez.hi, ez.lo};
    x[i] = {Lanes4{dv[i], dv[i], dv[i], ea.hi}, Lanes4{0.0, 0.0, 0.0, ea.lo}};
  }
  const auto cr = cross_terms(y, z);
  return {dot_terms(x, cr), det3_absolute_term(x[0].h, x[1].h, x[2].h)};
}

// The relation-only fast path's layout: πa, πb, πc and den = d·((b − a) × (c − a)) in lanes 0..3, each a
// determinant of d and two rounded differences (lane 3 is π(b, c) seen from a: the same determinant with a in
// the origin's place, so the π's filter constant holds for it). num, needed only for a line through the
// triangle, is evaluated on its own (triangle_num_filter).
[[nodiscard]] [[gnu::always_inline]] inline TriangleLanes<FilterTerm<Lanes4>> triangle_relation_lanes(
    const Ray& ray, const Triangle& triangle) noexcept {
  const Vec3 &a = triangle.a, &b = triangle.b, &c = triangle.c, &o = ray.origin, &d = ray.direction;
  const double av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z}, cv[3] = {c.x, c.y, c.z}, ov[3] = {o.x, o.y, o.z};
  const double dv[3] = {d.x, d.y, d.z};
  std::array<FilterLeaf<Lanes4>, 3> y, z, x;
  for (std::size_t i = 0; i < 3; ++i) {
    const Lanes4 from{ov[i], ov[i], ov[i], av[i]};
    y[i] = {Lanes4{bv[i], cv[i], av[i], bv[i]} - from};
    z[i] = {Lanes4{cv[i], av[i], bv[i], cv[i]} - from};
    x[i] = {broadcast<Lanes4>(dv[i])};
  }
  const auto cr = cross_terms(y, z);
  return {dot_terms(x, cr), det3_absolute_term(x[0].v, x[1].v, x[2].v)};
}

// The same four values for four triangles at once, triangle k in lane k (the leaves of a mesh's BVH, in structure
// of arrays): πa, πb, πc and den as four Lanes4, lane k of each computed by exactly the operations of
// triangle_relation_lanes' lane for that value on triangle k (so the same bits: tests/triangle_stages_test.cpp).
struct TriangleRelationColumns {
  FilterTerm<Lanes4> pi[3], den;
  Lanes4 absolute;  // d's absolute term, the same in every lane
};
[[nodiscard]] [[gnu::always_inline]] inline TriangleRelationColumns triangle_relation_columns(
    const Ray& ray, const Triangle* const t[4]) noexcept {
  const double ov[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double dv[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const auto coordinate = [](const Vec3& v, std::size_t i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); };
  const auto column = [&](const Vec3 Triangle::*vertex, std::size_t i) {
    return Lanes4{coordinate(t[0]->*vertex, i), coordinate(t[1]->*vertex, i), coordinate(t[2]->*vertex, i),
                  coordinate(t[3]->*vertex, i)};
  };
  std::array<FilterLeaf<Lanes4>, 3> ea, eb, ec, ab, ac, x;
  for (std::size_t i = 0; i < 3; ++i) {
    const Lanes4 a = column(&Triangle::a, i), b = column(&Triangle::b, i), c = column(&Triangle::c, i);
    const Lanes4 from{ov[i], ov[i], ov[i], ov[i]};
    ea[i] = {a - from};
    eb[i] = {b - from};
    ec[i] = {c - from};
    ab[i] = {b - a};
    ac[i] = {c - a};
    x[i] = {broadcast<Lanes4>(dv[i])};
  }
  return {{dot_terms(x, cross_terms(eb, ec)), dot_terms(x, cross_terms(ec, ea)), dot_terms(x, cross_terms(ea, eb))},
          dot_terms(x, cross_terms(ab, ac)),
          det3_absolute_term(x[0].v, x[1].v, x[2].v)};
}

// The screen of four triangles (a leaf of a mesh's BVH), from the same values as fast_triangle_relation's first
// decision (triangle/ray_triangle_cascade.cpp, fast_relation) for each: bit k of `missed`, triangle k is certainly
// missed — the four stage-1 signs certain and not all den's ("outside", under either rule); bit k of `inside`, the
// four signs certain and all den's — a line through the interior, whose relation fast_relation then decides from
// num alone (inside_relation below), with den's stage-1 value and sign, lane k here. Neither bit: the signs are
// not all certain, fast_relation's own path.
// Certified by: proofs/triangle/TriangleCascadeTwins.v, `fast_relation_tri_correct` (the decision, on these values);
// tied by the twin runner's routine tri_leaf_screen (proofs/twins/Extract.v, TriScreen: bit k of the misses against
// fast_relation_tri_b answering a miss for triangle k, in every lane variant) and by tests/triangle_stages_test.cpp
// (lane k here is fast_relation's values of triangle k, bit for bit; the inside bits are its inside branch).
struct TriangleScreen {
  unsigned missed = 0, inside = 0;
  // Set only when some lane is inside (read for those lanes only):
  FilterTerm<Lanes4> den;  // den = d·((b − a) × (c − a)) of each triangle, stage 1
  Mask4 den_sign;          // its certified sign where `inside` (Sign's values)
  double absolute;         // d's absolute term, every lane's
};
// triangle_screen into `r` (a screen kept across calls: the mesh queries' LeafScreen).
[[gnu::always_inline]] inline void triangle_screen(const Ray& ray, const Triangle* const t[4], TriangleScreen& r) noexcept {
  const TriangleRelationColumns v = triangle_relation_columns(ray, t);
  const Mask4 sa = det3_filter_lanes(v.pi[0], bounds::triangle_filter_pi_relative, v.absolute);
  const Mask4 sb = det3_filter_lanes(v.pi[1], bounds::triangle_filter_pi_relative, v.absolute);
  const Mask4 sc = det3_filter_lanes(v.pi[2], bounds::triangle_filter_pi_relative, v.absolute);
  const Mask4 sden = det3_filter_lanes(v.den, bounds::triangle_filter_pi_relative, v.absolute);
  const Mask4 certain = (sa != uncertain_lane) & (sb != uncertain_lane) & (sc != uncertain_lane) & (sden != uncertain_lane);
  const Mask4 inside = (sa == sden) & (sb == sden) & (sc == sden);
  const Mask4 miss = certain & ~inside;
  const Mask4 through = certain & inside;
  // Both masks' bits in one reduction: lane k contributes 2^k when missed and 2^(k + 4) when inside.
  const Mask4 weights = (miss & Mask4{1, 2, 4, 8}) | (through & Mask4{16, 32, 64, 128});
  const auto bits = static_cast<unsigned>((weights[0] | weights[1]) | (weights[2] | weights[3]));
  const unsigned inside_bits = bits >> 4;
  r.missed = bits & 15u;
  r.inside = inside_bits;
  if (inside_bits != 0) {  // read only for these lanes
    r.den = v.den;
    r.den_sign = sden;
    r.absolute = v.absolute[0];
  }
}
[[nodiscard]] [[gnu::always_inline]] inline TriangleScreen triangle_screen(const Ray& ray,
                                                                          const Triangle* const t[4]) noexcept {
  TriangleScreen r;
  triangle_screen(ray, t, r);
  return r;
}

// Bit k: triangle k is certainly missed (triangle_screen's `missed`).
[[nodiscard]] [[gnu::always_inline]] inline unsigned triangle_certain_misses(const Ray& ray,
                                                                            const Triangle* const t[4]) noexcept {
  return triangle_screen(ray, t).missed;
}

// num = ê_a·(ê_b × ê_c) in stage 1, with its absolute term.
struct TriangleNumFilter {
  FilterTerm<double> value;
  double absolute;
};
[[nodiscard]] [[gnu::always_inline]] inline TriangleNumFilter triangle_num_filter(const Ray& ray,
                                                                                  const Triangle& triangle) noexcept {
  const auto leaves = ray_triangle_leaves<FilterLeaf<double>>(
      ray, triangle, [](double x) { return FilterLeaf<double>{x}; },
      [](double v, double w) { return FilterLeaf<double>{v - w}; });
  const auto& [ea, eb, ec] = leaves.e;
  return {dot_terms(ea, cross_terms(eb, ec)), det3_absolute_term(ea[0].v, ea[1].v, ea[2].v)};
}

// Lane k of a lane value, as a scalar value.
[[nodiscard]] [[gnu::always_inline]] inline FilterTerm<double> lane(const FilterTerm<Lanes4>& t, int k) noexcept {
  return {t.v[k], t.m[k]};
}
[[nodiscard]] [[gnu::always_inline]] inline CompensatedTerm<double> lane(const CompensatedTerm<Lanes4>& t,
                                                                         int k) noexcept {
  return {t.h[k], t.l[k], t.m[k]};
}

// Stage 2 of one query (triangle_compensated_values' five values) from the fast path's layout: πa, πb, πc and
// num by one Lanes4 evaluation (triangle_compensated_lanes), den = (πa + πb) + πc summed in scalar as
// ray_triangle_terms sums it. The same bits as triangle_compensated_values (tested:
// tests/triangle_stages_test.cpp) up to the sign of a zero (triangle_compensated_lanes' broadcast), which no
// decision sees: the filter and the enclosures compare with strict inequalities against bounds ≥ 0, and never
// certify a zero. What the full cascade (ray_triangle_cascade.cpp) evaluates first: it runs when the fast path
// left a sign open, and then stage 2 is almost always needed (stage 1 is its filter view).
[[nodiscard]] [[gnu::always_inline]] inline TriangleCompensatedValues triangle_compensated_values_of(
    const TriangleLanes<CompensatedTerm<Lanes4>>& s2) noexcept {
  const CompensatedTerm<double> pa = lane(s2.lanes, 0), pb = lane(s2.lanes, 1), pc = lane(s2.lanes, 2);
  return {{pa, pb, pc, (pa + pb) + pc, lane(s2.lanes, lane_num)}, s2.absolute[0], s2.absolute[lane_num]};
}
[[nodiscard]] [[gnu::always_inline]] inline TriangleCompensatedValues triangle_compensated_values_by_lanes(
    const Ray& ray, const Triangle& triangle) noexcept {
  return triangle_compensated_values_of(triangle_compensated_lanes(ray, triangle));
}

// Stage 2's values as the fast path leaves them for the cascade (triangle/ray_triangle_cascade.hpp): `computed`
// when it evaluated them (the same lanes, so the same bits as triangle_compensated_values_by_lanes).
struct TriangleStage2Handover {
  TriangleCompensatedValues values;
  bool computed = false;
};

// ---- t = num/den alone: what a nearest hit compares and rounds ---------------------------------------------
//
// A nearest hit orders its candidates by t and rounds the winner's t: it needs num and den, not the three π.
// den is taken in its short form d·((b − a) × (c − a)) — π(b, c) seen from a, lane 3 of
// triangle_relation_lanes — so the π's constants and theorems hold for it with a in the origin's place;
// num = ê_a·(ê_b × ê_c) as everywhere. The stage-3 expansions of the same two forms are value_expansion's
// value_num and value_den.
//   stage 1: |V − v| ≤ (C ⊗ m) ⊕ A, the bound det3_filter compares against (the instances num_filter_encloses and,
//            for den with o := a, pi_filter_encloses of the general theorem):
//            proofs/triangle/TriangleFilter.v, `det3_filter_encloses`
//   stage 2: det3_enclosure (den with o := a):
//            proofs/triangle/TriangleCompensated.v, `pi_compensated_encloses`, `num_compensated_encloses`

// Stage 1 of num and den (den in the short form), with their absolute terms: the values fast_triangle_relation
// decides a line through the triangle from (triangle/ray_triangle_cascade.hpp), or computed on their own.
struct TriangleQuotientStage1 {
  FilterTerm<double> num, den;
  double absolute_e, absolute_d;  // num's (ê_a) and den's (d)
};

// fast_relation's decision for a line through the triangle's interior (den and the three π certain, all of den's
// sign `den_sign`), from den's stage-1 value: num's stage-1 sign says hit (num's sign is den's) or behind, and is
// uncertain_lane when the filter cannot say; `values` are the stage-1 values of num and den it was decided from.
struct InsideRelation {
  std::int64_t num_sign;
  TriangleQuotientStage1 values;
  [[nodiscard]] TriangleClassification classification(std::int64_t den_sign) const noexcept {
    return {num_sign == den_sign ? TriangleRelation::hit : TriangleRelation::behind, TriangleLocation::inside, true};
  }
};
[[nodiscard]] [[gnu::always_inline]] inline InsideRelation inside_relation(const Ray& ray, const Triangle& triangle,
                                                                          FilterTerm<double> den,
                                                                          double absolute_d) noexcept {
  const TriangleNumFilter num = triangle_num_filter(ray, triangle);
  return {det3_filter_lanes(num.value, bounds::triangle_filter_num_relative, num.absolute),
          {num.value, den, num.absolute, absolute_d}};
}

template <class Leaf>
[[nodiscard]] [[gnu::always_inline]] inline std::array<Leaf, 3> leaf_differences(const Vec3& v, const Vec3& from,
                                                                                 auto difference) noexcept {
  return {difference(v.x, from.x), difference(v.y, from.y), difference(v.z, from.z)};
}

[[nodiscard]] [[gnu::always_inline]] inline TriangleQuotientStage1 triangle_quotient_filter(const Ray& ray,
                                                                                           const Triangle& t) noexcept {
  const auto difference = [](double v, double w) { return FilterLeaf<double>{v - w}; };
  const Vec3 &o = ray.origin, &d = ray.direction;
  const std::array<FilterLeaf<double>, 3> dl{FilterLeaf<double>{d.x}, FilterLeaf<double>{d.y}, FilterLeaf<double>{d.z}};
  const auto ea = leaf_differences<FilterLeaf<double>>(t.a, o, difference);
  const auto eb = leaf_differences<FilterLeaf<double>>(t.b, o, difference);
  const auto ec = leaf_differences<FilterLeaf<double>>(t.c, o, difference);
  const auto ab = leaf_differences<FilterLeaf<double>>(t.b, t.a, difference);
  const auto ac = leaf_differences<FilterLeaf<double>>(t.c, t.a, difference);
  return {dot_terms(ea, cross_terms(eb, ec)), dot_terms(dl, cross_terms(ab, ac)),
          det3_absolute_term(ea[0].v, ea[1].v, ea[2].v), det3_absolute_term(d.x, d.y, d.z)};
}

// Stage 2 of num and den (den in the short form): their enclosures.
struct TriangleQuotientStage2 {
  Enclosure num, den;
};

[[nodiscard]] [[gnu::always_inline]] inline CompensatedLeaf<double> compensated_difference(double v, double w) noexcept {
  const DoubleDouble s = two_diff(v, w);
  return CompensatedLeaf<double>{s.hi, s.lo};
}

// Stage 2 of num alone, for a ray from o: (a − o)·((b − o) × (c − o)) (spawn's side of a point, σ(o), is its
// opposite sign: spawn/spawn_certified.cpp).
[[nodiscard]] [[gnu::always_inline]] inline Enclosure triangle_num_compensated(const Vec3& o,
                                                                               const Triangle& t) noexcept {
  const auto ea = leaf_differences<CompensatedLeaf<double>>(t.a, o, compensated_difference);
  const auto eb = leaf_differences<CompensatedLeaf<double>>(t.b, o, compensated_difference);
  const auto ec = leaf_differences<CompensatedLeaf<double>>(t.c, o, compensated_difference);
  return det3_enclosure(dot_terms(ea, cross_terms(eb, ec)), bounds::triangle_compensated_relative,
                        det3_absolute_term(ea[0].h, ea[1].h, ea[2].h));
}

// Stage 2 of den alone (the short form): d·((b − a) × (c − a)).
[[nodiscard]] [[gnu::always_inline]] inline Enclosure triangle_den_compensated(const Vec3& d, const Triangle& t) noexcept {
  const std::array<CompensatedLeaf<double>, 3> dl{CompensatedLeaf<double>{d.x, 0.0}, CompensatedLeaf<double>{d.y, 0.0},
                                                  CompensatedLeaf<double>{d.z, 0.0}};
  const auto ab = leaf_differences<CompensatedLeaf<double>>(t.b, t.a, compensated_difference);
  const auto ac = leaf_differences<CompensatedLeaf<double>>(t.c, t.a, compensated_difference);
  return det3_enclosure(dot_terms(dl, cross_terms(ab, ac)), bounds::triangle_compensated_relative,
                        det3_absolute_term(d.x, d.y, d.z));
}

[[nodiscard]] [[gnu::always_inline]] inline TriangleQuotientStage2 triangle_quotient_compensated(
    const Ray& ray, const Triangle& t) noexcept {
  return {triangle_num_compensated(ray.origin, t), triangle_den_compensated(ray.direction, t)};
}

// sign(a·b − c·e) exactly, when both TwoProducts are exact (ExpansionBuilder's guard: a zero factor, or
// |a ⊗ b| ≥ 2^-968) and finite: the pairs (h, l) = TwoProduct are RN-normalised (h = RN(a·b)), so different h
// order the exact products as they are ordered (proofs/core/RoundOrder.v, `rne_compare_distinct`), and equal h
// leave a·b − c·e = l₁ − l₂, ordered as l₁ and l₂. Nothing when a guard fails.
//   Certified by: proofs/triangle/TieBreakPairs.v, `pair_difference_sign`.
[[nodiscard]] inline std::optional<int> product_difference_sign(double a, double b, double c, double e) noexcept {
  ExpansionBuilder builder;
  const DoubleDouble x = builder.product(a, b), y = builder.product(c, e);
  if (!builder.exact()) return std::nullopt;
  if (x.hi != y.hi) return x.hi > y.hi ? 1 : -1;
  return (x.lo > y.lo) - (x.lo < y.lo);
}

// A double as a leaf of the formulas whose products and differences are only recorded: cross_terms over these
// gives each component d_j·e_k − d_k·e_j as its four factors, in the formula's own order, for
// product_difference_sign.
struct RecordedLeaf {
  double value;
};
struct RecordedProduct {
  double a, b;
};
struct RecordedDifference {
  RecordedProduct left, right;
};
[[nodiscard]] inline RecordedProduct operator*(RecordedLeaf x, RecordedLeaf y) noexcept { return {x.value, y.value}; }
[[nodiscard]] inline RecordedDifference operator-(RecordedProduct x, RecordedProduct y) noexcept { return {x, y}; }

// The tie-break vector d × (q − p) of the directed edge p → q (ray_triangle_formula.hpp's edge_tie_break) in exact
// expansions, for a direction given as expansion leaves — a ray's d lifted, or a segment's exact q − p as TwoDiff
// pairs (docs/contract.md §8) — as exact signs of its x, y, z components, or nothing when an expansion was not
// exact (an underflow or overflow) or its sign not certain. Each component is leaf·leaf − leaf·leaf: at most 16
// components (expansion_value.hpp's capacities; exact by proofs/core/Expansions.v, `scale_gen_exact` and
// `sum_gen_exact`, its sign by `expansion_sign_sound`). When every leaf is one double (a ray's d, and q − p exact
// in binary64: its TwoDiff tail 0), each component is decided first by product_difference_sign, without an
// expansion.
[[nodiscard]] inline std::optional<std::array<int, 3>> edge_tie_break_signs_by_expansion(
    const std::array<ExpansionValue<2>, 3>& d, const Vec3& p, const Vec3& q) noexcept {
  {  // each component from two TwoProducts: cross_terms over recorded leaves names its four factors
    const double qv[3] = {q.x, q.y, q.z}, pv[3] = {p.x, p.y, p.z};
    std::array<RecordedLeaf, 3> e{}, dv{};
    bool single = true;
    for (std::size_t i = 0; i < 3; ++i) {
      const DoubleDouble t = two_diff(qv[i], pv[i]);
      e[i] = {t.hi};
      dv[i] = {d[i].e.component[0]};
      single = single && t.lo == 0 && std::isfinite(t.hi) && d[i].exact && d[i].e.size == 1;
    }
    if (single) {
      const std::array<RecordedDifference, 3> terms = cross_terms(dv, e);
      std::array<int, 3> s{};
      std::size_t i = 0;
      for (; i < 3; ++i) {
        const RecordedDifference& t = terms[i];
        const std::optional<int> sign = product_difference_sign(t.left.a, t.left.b, t.right.a, t.right.b);
        if (!sign) break;
        s[i] = *sign;
      }
      if (i == 3) return s;
    }
  }
  const auto v = edge_tie_break(d, p, q, expansion_difference);
  std::array<int, 3> s{};
  for (std::size_t i = 0; i < 3; ++i) {
    const Sign sign = v[i].sign();
    if (!is_certain(sign)) return std::nullopt;
    s[i] = static_cast<int>(sign);
  }
  return s;
}

// The tie-break vector d × (q − p) of π's edge (0: b → c, 1: c → a, 2: a → b) as exact signs of its x, y, z
// components, or nothing when an expansion was not exact or its sign not certain.
[[nodiscard]] inline std::optional<std::array<int, 3>> tie_break_signs_by_expansion(const Ray& ray,
                                                                                     const Triangle& triangle,
                                                                                     int k) noexcept {
  // Only edge k's vector: d × (q − p) for b → c, c → a, a → b.
  const Vec3& p = k == 0 ? triangle.b : k == 1 ? triangle.c : triangle.a;
  const Vec3& q = k == 0 ? triangle.c : k == 1 ? triangle.a : triangle.b;
  const Vec3& d = ray.direction;
  return edge_tie_break_signs_by_expansion({expansion_of(d.x), expansion_of(d.y), expansion_of(d.z)}, p, q);
}

// Whether N = (b − a) × (c − a) is the zero vector, exactly, or nothing when an expansion was not exact or its sign not certain.
[[nodiscard]] inline std::optional<bool> normal_is_zero_by_expansion(const Triangle& triangle) noexcept {
  const auto n = triangle_normal<ExpansionValue<2>>(triangle, expansion_difference);
  bool zero = true;
  for (std::size_t i = 0; i < 3; ++i) {
    const Sign sign = n[i].sign();
    if (!is_certain(sign)) return std::nullopt;
    zero = zero && sign == Sign::zero;
  }
  return zero;
}

}  // namespace raykernel::detail
