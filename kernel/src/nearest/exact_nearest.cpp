// The exact stage of the nearest-hit module across kinds, and the reference nearest_hit_exact of a scene: GMP
// rationals from the doubles' bits (rational_from_double.hpp), the formulas of docs/contract.md §1 and §6.
#include "nearest/exact_nearest.hpp"

#include <raykernel/nearest_scene.hpp>

#include "core/fp_environment.hpp"
#include "core/rational_from_double.hpp"
#include "plane/ray_plane_formula.hpp"

#include <gmpxx.h>

#include <array>
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

}  // namespace

int compare_plane_triangle_t(const Ray& ray, const Plane& plane, const Triangle& triangle) {
  const RayPlaneValues<mpq_class> p = ray_plane_values<mpq_class>(ray, plane, rational_from_double);
  const Quotient q = triangle_quotient(ray, triangle);
  return sign_of(cmp(mpq_class(p.num / p.den), mpq_class(q.num / q.den)));
}

QuotientSigns triangle_quotient_signs(const Ray& ray, const Triangle& triangle) {
  const Quotient q = triangle_quotient(ray, triangle);
  return {sgn(q.num), sgn(q.den)};
}

}  // namespace raykernel::detail::exact

namespace raykernel {

std::optional<SurfaceHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes, const Mesh* mesh,
                                            TriangleRule rule, const NearestOptions& options) {
  return detail::in_default_fp_environment([&]() -> std::optional<SurfaceHit> {
    if (auto reason = validate(ray)) throw invalid_input(*reason);
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (auto reason = validate(planes[k])) throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
    if (mesh != nullptr)
      if (const auto problem = validate(*mesh)) throw invalid_input("mesh: " + *problem);
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    std::optional<SurfaceHit> best;
    mpq_class best_t;
    // Planes first, then triangles, each in index order: a strictly smaller t wins, so an exact tie keeps the
    // plane, then the smaller index.
    for (std::size_t k = 0; k < planes.size(); ++k) {
      const ExactIntersection e = intersect_exact_rational(ray, planes[k]);
      if (e.intersection.relation != Relation::hit) continue;
      mpq_class t = detail::exact::rational(*e.t);
      if (best && cmp(t, best_t) >= 0) continue;
      best_t = std::move(t);
      best = SurfaceHit{SurfaceKind::plane, k, e.intersection.t, {nan, nan, nan}};
    }
    if (mesh != nullptr)
      for (std::size_t k = 0; k < mesh->triangles.size(); ++k) {
        const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh->triangle(k), rule);
        if (e.intersection.relation != TriangleRelation::hit) continue;
        mpq_class t = detail::exact::rational(*e.t);
        if (best && cmp(t, best_t) >= 0) continue;
        best_t = std::move(t);
        best = SurfaceHit{SurfaceKind::triangle, k, e.intersection.t, {nan, nan, nan}};
        if (options.barycentric) best->barycentric = e.intersection.barycentric;
      }
    return best;
  });
}

}  // namespace raykernel
