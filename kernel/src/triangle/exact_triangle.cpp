// The exact ray–triangle stage: ray_triangle_formula.hpp instantiated with GMP's mpq_class, doubles converted
// from their bits (rational_from_double.hpp), quotients rounded by MPFR (binary64_rounding.hpp). No CGAL here,
// so this translation unit compiles quickly.
#include "triangle/exact_triangle.hpp"

#include "core/binary64_rounding.hpp"
#include "core/exact_value.hpp"
#include "core/rational_from_double.hpp"
#include "triangle/ray_triangle_formula.hpp"

#include <gmpxx.h>

#include <limits>

namespace raykernel::detail::exact {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

RayTriangleTerms<Exact> exact_terms(const Ray& ray, const Triangle& triangle) {
  return ray_triangle_terms<Exact>(ray, triangle, lift, difference);
}

TriangleClassification classify(const Ray& ray, const Triangle& triangle, const RayTriangleTerms<Exact>& t,
                                TriangleRule rule) {
  return detail::classify_triangle(
      rule, [&] { return sgn(t.den); }, [&](int k) { return sgn(t.pi[static_cast<std::size_t>(k)]); },
      [&](int k) {
        const auto v = triangle_tie_breaks<Exact>(ray, triangle, lift, difference)[static_cast<std::size_t>(k)];
        return std::array<int, 3>{sgn(v[0]), sgn(v[1]), sgn(v[2])};
      },
      [&] { return sgn(t.num); },
      [&] {
        const auto n = triangle_normal<Exact>(triangle, difference);
        return sgn(n[0]) == 0 && sgn(n[1]) == 0 && sgn(n[2]) == 0;
      });
}

TriangleIntersection with_roundings(const TriangleClassification& c, const RayTriangleTerms<Exact>& t,
                                    bool want_t, bool want_barycentric) {
  TriangleIntersection r{c.relation, c.location, c.owned, not_a_number, {not_a_number, not_a_number, not_a_number}};
  if (c.location == TriangleLocation::none) return r;
  if (want_t) r.t = round_rational_to_nearest_even(t.num.q / t.den.q);  // 0/den is the canonical 0: +0
  if (want_barycentric)
    for (std::size_t k = 0; k < 3; ++k) r.barycentric[k] = round_rational_to_nearest_even(t.pi[k].q / t.den.q);
  return r;
}

}  // namespace

TriangleIntersection intersect_triangle(const Ray& ray, const Triangle& triangle, const TriangleOptions& options) {
  const RayTriangleTerms<Exact> t = exact_terms(ray, triangle);
  return with_roundings(classify(ray, triangle, t, options.rule), t, options.t, options.barycentric);
}

ExactTriangleIntersection intersect_triangle_rational(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  const RayTriangleTerms<Exact> t = exact_terms(ray, triangle);
  ExactTriangleIntersection x{with_roundings(classify(ray, triangle, t, rule), t, true, true),
                              to_public(t.den.q),
                              to_public(t.num.q),
                              to_public(t.pi[0].q),
                              to_public(t.pi[1].q),
                              to_public(t.pi[2].q),
                              std::nullopt,
                              std::nullopt};
  if (sgn(t.den) != 0) {
    x.t = to_public(t.num.q / t.den.q);
    x.barycentric = {to_public(t.pi[0].q / t.den.q), to_public(t.pi[1].q / t.den.q), to_public(t.pi[2].q / t.den.q)};
  }
  return x;
}

TriangleClassification classify_triangle(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  return classify(ray, triangle, exact_terms(ray, triangle), rule);
}

TriangleRoundings round_triangle_quotients(const Ray& ray, const Triangle& triangle, bool t, bool barycentric) {
  const RayTriangleTerms<Exact> terms = exact_terms(ray, triangle);
  const TriangleIntersection r = with_roundings({TriangleRelation::miss, TriangleLocation::outside, false}, terms, t,
                                                barycentric);
  return {r.t, r.barycentric};
}

}  // namespace raykernel::detail::exact
