// The exact stage of the nearest-hit module across kinds, and the reference nearest_hit_exact of a scene: GMP
// rationals from the doubles' bits (rational_from_double.hpp), the formulas of docs/contract.md §1 and §6.
#include "nearest/exact_nearest.hpp"

#include <raykernel/nearest_scene.hpp>

#include "core/fp_environment.hpp"
#include "core/rational_from_double.hpp"
#include "plane/ray_plane_formula.hpp"
#include "sphere/ray_sphere_formula.hpp"

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace raykernel::detail::exact {
namespace {

using Point = std::array<mpq_class, 3>;

Point point(const Vec3& v) { return {rational_from_double(v.x), rational_from_double(v.y), rational_from_double(v.z)}; }

struct Quotient {
  mpq_class num, den;
};

// num = (a − o)·N and den = d·N, N = (b − a) × (c − a).
Quotient triangle_quotient(const Ray& ray, const Triangle& triangle) {
  const Point o = point(ray.origin), d = point(ray.direction);
  const Point a = point(triangle.a), b = point(triangle.b), c = point(triangle.c);
  Point e1, e2, ao;
  for (std::size_t k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], ao[k] = a[k] - o[k];
  const Point n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return {ao[0] * n[0] + ao[1] * n[1] + ao[2] * n[2], d[0] * n[0] + d[1] * n[1] + d[2] * n[2]};
}

int sign_of(int c) { return (c > 0) - (c < 0); }

// An exact rational from its decimal text (Rational, as intersect_exact_rational gives it).
mpq_class rational(const Rational& r) {
  mpq_class q(r.numerator + "/" + r.denominator);
  q.canonicalize();
  return q;
}

// An exact t of any kind as U + s·√V: a sphere's root (s = −1: t1, +1: t2, 0: the tangent root t0, with
// U = −B/A and V = D/A²), or a rational t (s = 0, V = 0).
struct Root {
  mpq_class u, v;
  int s;
};

Root sphere_root(const Ray& ray, const Sphere& sphere, int root) {
  const RaySphereTerms<mpq_class> t = ray_sphere_terms<mpq_class>(ray, sphere, rational_from_double, [](double x, double y) {
    return mpq_class(rational_from_double(x) - rational_from_double(y));
  });
  return {mpq_class(-t.b / t.a), mpq_class(t.d / (t.a * t.a)), root};
}

// sign(x + m·√v), v ≥ 0, for rationals x and m: the signs of the terms, and when they differ the sign of x² − m²v
// with x's sign.
int sign_plus_scaled_root(const mpq_class& x, const mpq_class& m, const mpq_class& v) {
  const int sx = sgn(x), sm = sgn(v) == 0 ? 0 : sgn(m);
  if (sm == 0) return sx;
  if (sx == 0 || sx == sm) return sm;
  return sx * sgn(mpq_class(x * x - m * m * v));
}

// sign(a − b) = sign(w + s_a√V_a − s_b√V_b), w = U_a − U_b: with α = w + s_a√V_a, the sign of α − s_b√V_b is
// α's when the second term is zero or of α's sign, and otherwise α's times the sign of
// α² − V_b = (w² + s_a²V_a − V_b) + 2·w·s_a·√V_a.
int compare_roots(const Root& a, const Root& b) {
  const mpq_class w = a.u - b.u;
  const int alpha = sign_plus_scaled_root(w, mpq_class(a.s), a.v);
  const int second = sgn(b.v) == 0 ? 0 : -b.s;  // the sign of −s_b·√V_b
  if (second == 0) return alpha;
  if (alpha == 0) return second;
  if (alpha == second) return alpha;
  const mpq_class k = w * w + (a.s == 0 ? mpq_class(0) : a.v) - b.v;
  return alpha * sign_plus_scaled_root(k, mpq_class(2 * w * a.s), a.v);
}

Root rational_root(mpq_class q) { return {std::move(q), mpq_class(0), 0}; }

}  // namespace

int compare_sphere_plane_t(const Ray& ray, const Sphere& sphere, int root, const Plane& plane) {
  const RayPlaneValues<mpq_class> p = ray_plane_values<mpq_class>(ray, plane, rational_from_double);
  return compare_roots(sphere_root(ray, sphere, root), rational_root(p.num / p.den));
}

int compare_sphere_triangle_t(const Ray& ray, const Sphere& sphere, int root, const Triangle& triangle) {
  const Quotient q = triangle_quotient(ray, triangle);
  return compare_roots(sphere_root(ray, sphere, root), rational_root(q.num / q.den));
}

int compare_sphere_sphere_t(const Ray& ray, const Sphere& a, int root_a, const Sphere& b, int root_b) {
  return compare_roots(sphere_root(ray, a, root_a), sphere_root(ray, b, root_b));
}

int compare_plane_triangle_t(const Ray& ray, const Plane& plane, const Triangle& triangle) {
  const RayPlaneValues<mpq_class> p = ray_plane_values<mpq_class>(ray, plane, rational_from_double);
  const Quotient q = triangle_quotient(ray, triangle);
  return sign_of(cmp(mpq_class(p.num / p.den), mpq_class(q.num / q.den)));
}

int compare_plane_t_with(const Ray& ray, const Plane& plane, double b) {
  const RayPlaneValues<mpq_class> p = ray_plane_values<mpq_class>(ray, plane, rational_from_double);
  return sign_of(cmp(mpq_class(p.num / p.den), rational_from_double(b)));
}

QuotientSigns triangle_quotient_signs(const Ray& ray, const Triangle& triangle) {
  const Quotient q = triangle_quotient(ray, triangle);
  return {sgn(q.num), sgn(q.den)};
}

}  // namespace raykernel::detail::exact

namespace raykernel {

std::optional<SphereHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval, std::span<const Sphere> spheres) {
  using detail::exact::Root;
  return detail::in_default_fp_environment([&]() -> std::optional<SphereHit> {
    if (auto reason = validate(ray)) throw invalid_input(*reason);
    if (auto reason = validate(interval)) throw invalid_input(*reason);
    for (std::size_t k = 0; k < spheres.size(); ++k)
      if (auto reason = validate(spheres[k])) throw invalid_input("sphere " + std::to_string(k) + ": " + *reason);
    const Root lo = detail::exact::rational_root(detail::exact::rational_from_double(interval.t_min));
    const bool bounded = !std::isinf(interval.t_max);  // a valid t_max is +inf or finite
    const Root hi = detail::exact::rational_root(bounded ? detail::exact::rational_from_double(interval.t_max) : mpq_class(0));
    std::optional<SphereHit> best;
    Root best_t;
    for (std::size_t k = 0; k < spheres.size(); ++k) {
      const SphereIntersection e = intersect_exact(ray, spheres[k]);
      if (e.relation == SphereRelation::miss) continue;
      const bool tangent = e.relation == SphereRelation::tangent;
      for (const int root : {-1, +1}) {
        if (tangent && root > 0) break;
        const Root t = detail::exact::sphere_root(ray, spheres[k], tangent ? 0 : root);
        if (detail::exact::compare_roots(t, lo) < 0) continue;
        if (bounded && detail::exact::compare_roots(t, hi) > 0) break;
        if (!best || detail::exact::compare_roots(t, best_t) < 0) {
          best_t = t;
          best = SphereHit{k, root < 0 ? e.t1 : e.t2};
        }
        break;  // the smaller root in the interval is this sphere's hit
      }
    }
    return best;
  });
}

std::optional<NearestHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval, std::span<const Plane> planes) {
  return detail::in_default_fp_environment([&]() -> std::optional<NearestHit> {
    if (auto reason = validate(ray)) throw invalid_input(*reason);
    if (auto reason = validate(interval)) throw invalid_input(*reason);
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (auto reason = validate(planes[k])) throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
    const mpq_class lo = detail::exact::rational_from_double(interval.t_min);
    const bool bounded = !std::isinf(interval.t_max);  // a valid t_max is +inf or finite
    const mpq_class hi = bounded ? detail::exact::rational_from_double(interval.t_max) : mpq_class(0);
    std::optional<NearestHit> best;
    mpq_class best_t;
    for (std::size_t k = 0; k < planes.size(); ++k) {  // a strictly smaller t wins: a tie keeps the smaller index
      const ExactIntersection e = intersect_exact_rational(ray, planes[k]);
      if (e.intersection.relation != Relation::hit) continue;
      const mpq_class t = detail::exact::rational(*e.t);
      if (t < lo || (bounded && t > hi) || (best && t >= best_t)) continue;
      best_t = t;
      best = NearestHit{k, e.intersection.t};
    }
    return best;
  });
}

std::optional<SurfaceHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes, const Mesh* mesh,
                                            TriangleRule rule, const NearestOptions& options) {
  return nearest_hit_exact(ray, planes, mesh, {}, rule, options);
}

std::optional<SurfaceHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes, const Mesh* mesh,
                                            std::span<const Sphere> spheres, TriangleRule rule,
                                            const NearestOptions& options) {
  using detail::exact::Root;
  return detail::in_default_fp_environment([&]() -> std::optional<SurfaceHit> {
    if (auto reason = validate(ray)) throw invalid_input(*reason);
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (auto reason = validate(planes[k])) throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
    if (mesh != nullptr)
      if (const auto problem = validate(*mesh)) throw invalid_input("mesh: " + *problem);
    for (std::size_t k = 0; k < spheres.size(); ++k)
      if (auto reason = validate(spheres[k])) throw invalid_input("sphere " + std::to_string(k) + ": " + *reason);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    std::optional<SurfaceHit> best;
    Root best_t;
    // Planes first, then triangles, then spheres, each in index order: a strictly smaller t wins, so an exact tie
    // keeps the plane, then the triangle, then the smaller index.
    const auto nearer = [&](const Root& t) { return !best || detail::exact::compare_roots(t, best_t) < 0; };
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const ExactIntersection e = intersect_exact_rational(ray, planes[k]);
      if (e.intersection.relation != Relation::hit) continue;
      Root t = detail::exact::rational_root(detail::exact::rational(*e.t));
      if (!nearer(t)) continue;
      best_t = std::move(t);
      best = SurfaceHit{SurfaceKind::plane, k, e.intersection.t, {nan, nan, nan}};
    }
    if (mesh != nullptr)
      for (std::size_t k = 0; k < mesh->triangles.size(); ++k) {
        const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh->triangle(k), rule);
        if (e.intersection.relation != TriangleRelation::hit) continue;
        Root t = detail::exact::rational_root(detail::exact::rational(*e.t));
        if (!nearer(t)) continue;
        best_t = std::move(t);
        best = SurfaceHit{SurfaceKind::triangle, k, e.intersection.t, {nan, nan, nan}};
        if (options.barycentric) best->barycentric = e.intersection.barycentric;
      }
    // A sphere's hit is its smallest root t ≥ 0 (docs/contract.md §10), its sign decided in rationals.
    const Root zero = detail::exact::rational_root(mpq_class(0));
    for (std::size_t k = 0; k < spheres.size(); ++k) {
      const SphereIntersection e = intersect_exact(ray, spheres[k]);
      if (e.relation == SphereRelation::miss) continue;
      const bool tangent = e.relation == SphereRelation::tangent;
      Root t = detail::exact::sphere_root(ray, spheres[k], tangent ? 0 : -1);
      double rounded = e.t1;
      if (detail::exact::compare_roots(t, zero) < 0) {
        if (tangent) continue;
        t.s = +1;
        rounded = e.t2;
        if (detail::exact::compare_roots(t, zero) < 0) continue;
      }
      if (!nearer(t)) continue;
      best_t = std::move(t);
      best = SurfaceHit{SurfaceKind::sphere, k, rounded, {nan, nan, nan}};
    }
    return best;
  });
}

}  // namespace raykernel
