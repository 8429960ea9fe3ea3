// The exact stage of the interval and segment queries (occlusion/exact_occlusion.hpp): ray_triangle_formula.hpp
// in GMP rationals, every double converted from its bits, so the answers do not depend on the floating-point
// environment. No CGAL.
#include "occlusion/exact_occlusion.hpp"

#include "core/rational_from_double.hpp"
#include "triangle/ray_triangle_formula.hpp"

#include <gmpxx.h>

namespace raykernel::detail::exact {
namespace {

// mpq_class without expression templates, so that the formulas' types are values.
struct Exact {
  mpq_class q;
};
Exact operator+(const Exact& a, const Exact& b) { return {a.q + b.q}; }
Exact operator-(const Exact& a, const Exact& b) { return {a.q - b.q}; }
Exact operator*(const Exact& a, const Exact& b) { return {a.q * b.q}; }
int sign_of(const Exact& a) { return sgn(a.q); }

Exact lift(double x) { return {rational_from_double(x)}; }
Exact difference(double v, double w) { return {rational_from_double(v) - rational_from_double(w)}; }

std::array<int, 3> signs(const std::array<Exact, 3>& v) { return {sign_of(v[0]), sign_of(v[1]), sign_of(v[2])}; }

}  // namespace

int compare_triangle_t_with(const Ray& ray, const Triangle& triangle, double b) {
  const RayTriangleTerms<Exact> t = ray_triangle_terms<Exact>(ray, triangle, lift, difference);
  const mpq_class delta = t.num.q - rational_from_double(b) * t.den.q;
  return sgn(delta) * sgn(t.den.q);
}

std::array<int, 3> segment_tie_break_signs(const Vec3& p, const Vec3& q, const Vec3& u, const Vec3& v) {
  return signs(edge_tie_break(difference_leaves<Exact>(p, q, difference), u, v, difference));
}

bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Triangle& triangle, TriangleRule rule) {
  // The line from p along d = q − p, exactly: the leaves of ray_triangle_formula.hpp with d as differences.
  auto e = [&](const Vec3& v) { return difference_leaves<Exact>(p, v, difference); };
  const RayTriangleLeaves<Exact> leaves{difference_leaves<Exact>(p, q, difference), {e(triangle.a), e(triangle.b), e(triangle.c)}};
  const auto t = ray_triangle_terms(leaves);
  const TriangleClassification c = classify_triangle(
      rule, [&] { return sign_of(t.den); }, [&](int k) { return sign_of(t.pi[static_cast<std::size_t>(k)]); },
      [&](int k) {
        const Vec3& u = k == 0 ? triangle.b : k == 1 ? triangle.c : triangle.a;
        const Vec3& v = k == 0 ? triangle.c : k == 1 ? triangle.a : triangle.b;
        return signs(edge_tie_break(leaves.d, u, v, difference));
      },
      [&] { return sign_of(t.num); },
      [&] {
        const auto n = triangle_normal<Exact>(triangle, difference);
        return sign_of(n[0]) == 0 && sign_of(n[1]) == 0 && sign_of(n[2]) == 0;
      });
  if (c.relation != TriangleRelation::hit) return false;
  const mpq_class ratio = t.num.q / t.den.q;  // den ≠ 0 for a hit
  return ratio > 0 && ratio < 1;
}

}  // namespace raykernel::detail::exact
