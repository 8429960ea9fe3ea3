// The per-query state of the certified ray–triangle cascade: the leaves, stage 1 or stage 2 values of the five
// determinants (πa, πb, πc, den, num), and stage 3 on demand. Used by the cascade (ray_triangle_cascade.cpp)
// and by the stage tests, which check each stage alone against exact rationals.
#pragma once

#include "certified/enclosure.hpp"
#include "certified/sign.hpp"
#include "certified/triangle_bounds.hpp"
#include "ray_triangle_formula.hpp"
#include "triangle/det3_stages.hpp"
#include "triangle/expansion_value.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <optional>

namespace raykernel::detail {

// Indices of the five determinants.
inline constexpr int value_pi_a = 0, value_pi_b = 1, value_pi_c = 2, value_den = 3, value_num = 4;
inline constexpr int triangle_value_count = 5;

// The relative constant of each determinant's filter and enclosure (triangle_bounds.hpp).
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
  ExpansionValue<576> den;
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

[[nodiscard]] inline TriangleExpansions triangle_expansions(const Ray& ray, const Triangle& triangle) noexcept {
  const auto t = ray_triangle_terms<ExpansionValue<2>>(ray, triangle, expansion_of, expansion_difference);
  return {{t.pi[0], t.pi[1], t.pi[2]}, t.den, t.num};
}

// ---- The fast path's layout: four determinants in the four lanes of a Lanes4 -------------------------------
//
// The three π and num share their structure: lane k of the leaves holds e_a, e_b, e_c, e_a (k = 0..3); the
// cross products' y and z are those leaves rotated by one and two lanes, so lane k computes c_a, c_b, c_c, c_a;
// the outer vector x is d in lanes 0–2 and e_a in lane 3. One evaluation of the formula's cross_terms and
// dot_terms on Lanes4 then gives πa, πb, πc and num in lanes 0..3, each lane performing exactly the scalar
// operations (so the same bits as triangle_filter_values / triangle_compensated_values, and the proofs' model
// for each value). den = (πa + πb) + πc is summed from the lanes in scalar.
inline constexpr int lane_num = 3;

[[nodiscard]] [[gnu::always_inline]] inline Lanes4 rotate_lanes_by_one(Lanes4 v) noexcept {
  return __builtin_shuffle(v, Mask4{1, 2, 0, 1});
}
[[nodiscard]] [[gnu::always_inline]] inline Lanes4 rotate_lanes_by_two(Lanes4 v) noexcept {
  return __builtin_shuffle(v, Mask4{2, 0, 1, 2});
}
// d in lanes 0–2, lane 3 of `e` (which holds e_a) in lane 3.
[[nodiscard]] [[gnu::always_inline]] inline Lanes4 d_and_lane_three(double d, Lanes4 e) noexcept {
  return Lanes4{d, d, d, e[3]};
}

template <class Term>
struct TriangleLanes {
  Term lanes;  // πa, πb, πc, num
  Lanes4 absolute;  // A_d, A_d, A_d, A_e
};

// The differences v − o of the vertices a, b, c, a in lanes, as `difference` makes them (rounded, or exact
// double-doubles).
struct LaneInputs {
  Lanes4 v[3];  // x, y, z components of a, b, c, a
  Lanes4 o[3];  // the origin, broadcast
  double d[3];
};
[[nodiscard]] [[gnu::always_inline]] inline LaneInputs lane_inputs(const Ray& ray, const Triangle& t) noexcept {
  const Vec3 &a = t.a, &b = t.b, &c = t.c, &o = ray.origin, &d = ray.direction;
  LaneInputs in;
  in.v[0] = Lanes4{a.x, b.x, c.x, a.x};
  in.v[1] = Lanes4{a.y, b.y, c.y, a.y};
  in.v[2] = Lanes4{a.z, b.z, c.z, a.z};
  in.o[0] = broadcast<Lanes4>(o.x);
  in.o[1] = broadcast<Lanes4>(o.y);
  in.o[2] = broadcast<Lanes4>(o.z);
  in.d[0] = d.x;
  in.d[1] = d.y;
  in.d[2] = d.z;
  return in;
}

[[nodiscard]] [[gnu::always_inline]] inline TriangleLanes<FilterTerm<Lanes4>> triangle_filter_lanes(
    const Ray& ray, const Triangle& triangle) noexcept {
  const LaneInputs in = lane_inputs(ray, triangle);
  std::array<FilterLeaf<Lanes4>, 3> y, z, x;
  for (std::size_t i = 0; i < 3; ++i) {
    const Lanes4 h = in.v[i] - in.o[i];
    y[i] = {rotate_lanes_by_one(h)};
    z[i] = {rotate_lanes_by_two(h)};
    x[i] = {d_and_lane_three(in.d[i], h)};
  }
  const auto c = cross_terms(y, z);
  return {dot_terms(x, c), det3_absolute_term(x[0].v, x[1].v, x[2].v)};
}

[[nodiscard]] [[gnu::always_inline]] inline TriangleLanes<CompensatedTerm<Lanes4>> triangle_compensated_lanes(
    const Ray& ray, const Triangle& triangle) noexcept {
  const LaneInputs in = lane_inputs(ray, triangle);
  std::array<CompensatedLeaf<Lanes4>, 3> y, z, x;
  for (std::size_t i = 0; i < 3; ++i) {
    const DD<Lanes4> e = two_diff(in.v[i], in.o[i]);
    y[i] = {rotate_lanes_by_one(e.hi), rotate_lanes_by_one(e.lo)};
    z[i] = {rotate_lanes_by_two(e.hi), rotate_lanes_by_two(e.lo)};
    x[i] = {d_and_lane_three(in.d[i], e.hi), d_and_lane_three(0.0, e.lo)};
  }
  const auto c = cross_terms(y, z);
  return {dot_terms(x, c), det3_absolute_term(x[0].h, x[1].h, x[2].h)};
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

// The tie-break vector d × (q − p) of π's edge (0: b → c, 1: c → a, 2: a → b) as exact signs of its x, y, z
// components, or nothing when an expansion was not exact.
[[nodiscard]] inline std::optional<std::array<int, 3>> tie_break_signs_by_expansion(const Ray& ray,
                                                                                     const Triangle& triangle,
                                                                                     int k) noexcept {
  const auto v = triangle_tie_breaks<ExpansionValue<2>>(ray, triangle, expansion_of,
                                                        expansion_difference)[static_cast<std::size_t>(k)];
  std::array<int, 3> s{};
  for (std::size_t i = 0; i < 3; ++i) {
    if (!v[i].exact) return std::nullopt;
    s[i] = static_cast<int>(v[i].e.sign());
  }
  return s;
}

// Whether N = (b − a) × (c − a) is the zero vector, exactly, or nothing when an expansion was not exact.
[[nodiscard]] inline std::optional<bool> normal_is_zero_by_expansion(const Triangle& triangle) noexcept {
  const auto n = triangle_normal<ExpansionValue<2>>(triangle, expansion_difference);
  bool zero = true;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!n[i].exact) return std::nullopt;
    zero = zero && n[i].e.sign() == Sign::zero;
  }
  return zero;
}

// The certified answer in the default floating-point environment (the cascade; validates what the fast path
// does not certify, throws invalid_input).
[[nodiscard]] TracedTriangleIntersection intersect_triangle_certified(const Ray& ray, const Triangle& triangle,
                                                                      const TriangleOptions& options);
[[nodiscard]] TriangleClassification triangle_relation_certified(const Ray& ray, const Triangle& triangle,
                                                                 TriangleRule rule);
struct TracedTriangleClassification {
  TriangleClassification classification;
  Stage stage;
};
[[nodiscard]] TracedTriangleClassification triangle_relation_traced(const Ray& ray, const Triangle& triangle,
                                                                    TriangleRule rule);

// The reason a ray/triangle is invalid input, or nothing (the triangle's own validation; to be expressed with
// the public validate(Ray) once it exists).
[[nodiscard]] std::optional<std::string> triangle_invalid_reason(const Ray& ray, const Triangle& triangle);

}  // namespace raykernel::detail
