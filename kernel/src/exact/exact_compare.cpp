// Exact signs and exact comparisons of t for nearest_hit: num and den as GMP rationals (mpq_class, the
// type behind CGAL::Exact_rational) through the same formula as every other path (ray_plane_formula.hpp).
// No CGAL here, so this translation unit compiles quickly; the rounding of t stays in exact_rational.cpp.
#include "exact/exact_compare.hpp"

#include "exact/rational_from_double.hpp"
#include "ray_plane_formula.hpp"

#include <gmpxx.h>

namespace raykernel::detail::exact {
namespace {

RayPlaneTerms<mpq_class> exact_terms(const Ray& ray, const Plane& plane) {
  return ray_plane_terms<mpq_class>(ray, plane, rational_from_double);
}

}  // namespace

ExactSigns ray_plane_signs(const Ray& ray, const Plane& plane) {
  const RayPlaneTerms<mpq_class> terms = exact_terms(ray, plane);
  return {sgn(terms.num), sgn(terms.den)};
}

int compare_quotients(const Ray& ray, const Plane& a, const Plane& b) {
  const RayPlaneTerms<mpq_class> ta = exact_terms(ray, a), tb = exact_terms(ray, b);
  return sgn(mpq_class(ta.num * tb.den - tb.num * ta.den));
}

std::optional<std::size_t> nearest_plane(const Ray& ray, std::span<const Plane> planes) {
  std::optional<std::size_t> best;
  mpq_class best_t;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const RayPlaneTerms<mpq_class> terms = exact_terms(ray, planes[k]);
    if (sgn(terms.den) == 0) continue;  // parallel or in-plane: never hit
    mpq_class t = terms.num / terms.den;
    if (sgn(t) < 0) continue;           // behind
    if (!best || t < best_t) {          // strictly smaller: ties keep the smaller index
      best = k;
      best_t = std::move(t);
    }
  }
  return best;
}

}  // namespace raykernel::detail::exact
