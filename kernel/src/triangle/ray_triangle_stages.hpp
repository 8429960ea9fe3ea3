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

[[nodiscard]] inline TriangleFilterValues triangle_filter_values(const Ray& ray, const Triangle& triangle) noexcept {
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

[[nodiscard]] inline TriangleCompensatedValues triangle_compensated_values(const Ray& ray,
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
