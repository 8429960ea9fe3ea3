// Exact signs for the mesh queries (mesh/exact_mesh.hpp): every value in GMP rationals, converted from the
// doubles' bits (rational_from_double.hpp), so the answers do not depend on the floating-point environment.
#include "mesh/exact_mesh.hpp"

#include "core/exact_value.hpp"
#include "core/rational_from_double.hpp"
#include "core/validation.hpp"

#include <gmpxx.h>

#include <array>

namespace raykernel::detail::exact {
namespace {

using Point = std::array<mpq_class, 3>;

Point point(const Vec3& v) { return {rational_from_double(v.x), rational_from_double(v.y), rational_from_double(v.z)}; }

int orient2d(const Point& p, const Point& q, const Point& r, int i, int j) {
  const auto si = static_cast<std::size_t>(i), sj = static_cast<std::size_t>(j);
  const mpq_class d = (p[si] - r[si]) * (q[sj] - r[sj]) - (p[sj] - r[sj]) * (q[si] - r[si]);
  return sgn(d);
}

bool within(const mpq_class& x, const mpq_class& a, const mpq_class& b) {
  return (a <= x && x <= b) || (b <= x && x <= a);
}

// t = num/den of the ray against the triangle (den ≠ 0).
mpq_class triangle_t(const Point& o, const Point& d, const Triangle& triangle) {
  const Point a = point(triangle.a), b = point(triangle.b), c = point(triangle.c);
  Point e1, e2, ao;
  for (std::size_t k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], ao[k] = a[k] - o[k];
  const Point n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const mpq_class num = ao[0] * n[0] + ao[1] * n[1] + ao[2] * n[2];
  const mpq_class den = d[0] * n[0] + d[1] * n[1] + d[2] * n[2];
  return num / den;
}

}  // namespace

int compare_triangle_t(const Ray& ray, const Triangle& first, const Triangle& second) {
  const Point o = point(ray.origin), d = point(ray.direction);
  const int c = cmp(triangle_t(o, d, first), triangle_t(o, d, second));
  return (c > 0) - (c < 0);
}

Rational rational_of_double(double x) { return to_public(rational_from_double(x)); }

bool rational_in_interval(const Rational& t, const RayInterval& interval) {
  if (compare_rationals(t, rational_of_double(interval.t_min)) < 0) return false;
  const bool bounded = is_finite(interval.t_max);
  return !bounded || compare_rationals(t, rational_of_double(interval.t_max)) <= 0;
}

int compare_rationals(const Rational& x, const Rational& y) {
  mpq_class a(x.numerator + "/" + x.denominator), b(y.numerator + "/" + y.denominator);
  a.canonicalize();
  b.canonicalize();
  const int c = cmp(a, b);
  return (c > 0) - (c < 0);
}

int orient2d_sign(const Vec3& p, const Vec3& q, const Vec3& r, int i, int j) {
  return orient2d(point(p), point(q), point(r), i, j);
}

int det3_sign(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Point po = point(o), pa = point(a), pb = point(b), pc = point(c);
  Point ea, eb, ec;
  for (std::size_t k = 0; k < 3; ++k) ea[k] = pa[k] - po[k], eb[k] = pb[k] - po[k], ec[k] = pc[k] - po[k];
  const mpq_class det = ea[0] * (eb[1] * ec[2] - eb[2] * ec[1]) + ea[1] * (eb[2] * ec[0] - eb[0] * ec[2]) +
                        ea[2] * (eb[0] * ec[1] - eb[1] * ec[0]);
  return sgn(det);
}

bool point_on_triangle(const Vec3& p, const Triangle& triangle) {
  const Point x = point(p), a = point(triangle.a), b = point(triangle.b), c = point(triangle.c);
  // Coplanar: det(a − p, b − p, c − p) = 0.
  if (det3_sign(p, triangle.a, triangle.b, triangle.c) != 0) return false;
  // N_k = ((b − a) × (c − a))_k is orient2d(b, c, a) in the plane of axes (k + 1, k + 2) mod 3.
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int n = orient2d(b, c, a, i, j);
    if (n == 0) continue;
    // The projection along k maps the triangle's plane one to one onto the (i, j) plane, keeping the triangle's
    // orientation n: p is in the closed triangle iff no edge sees it on the side opposite to n.
    return orient2d(a, b, x, i, j) != -n && orient2d(b, c, x, i, j) != -n && orient2d(c, a, x, i, j) != -n;
  }
  // Degenerate (N = 0): the triangle is the segment (or point) spanned by its collinear vertices, the union of
  // its three edges. p is on the edge [u, v] iff (v − u) × (p − u) = 0 and p is within their bounding box.
  const Point* edges[3][2] = {{&a, &b}, {&b, &c}, {&c, &a}};
  for (const auto& e : edges) {
    const Point &u = *e[0], &v = *e[1];
    bool on = true;
    for (int k = 0; k < 3 && on; ++k)
      on = orient2d(u, v, x, (k + 1) % 3, (k + 2) % 3) == 0 && within(x[static_cast<std::size_t>(k)],
                                                                       u[static_cast<std::size_t>(k)],
                                                                       v[static_cast<std::size_t>(k)]);
    if (on) return true;
  }
  return false;
}

}  // namespace raykernel::detail::exact
