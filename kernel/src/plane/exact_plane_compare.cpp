// Exact signs and exact comparisons of t for nearest_hit: num and den as GMP rationals (mpq_class, the
// type behind CGAL::Exact_rational) through the same formula as every other path (ray_plane_formula.hpp).
// No CGAL here, so this translation unit compiles quickly; the rounding of t stays in exact_rational.cpp.
#include "plane/exact_plane_compare.hpp"

#include "core/rational_from_double.hpp"
#include "plane/ray_plane_formula.hpp"

#include <gmpxx.h>

#include <map>
#include <string>

namespace raykernel::detail::exact {
namespace {

RayPlaneValues<mpq_class> exact_terms(const Ray& ray, const Plane& plane) {
  return ray_plane_values<mpq_class>(ray, plane, rational_from_double);
}

}  // namespace

ExactSigns ray_plane_signs(const Ray& ray, const Plane& plane) {
  const RayPlaneValues<mpq_class> terms = exact_terms(ray, plane);
  return {sgn(terms.num), sgn(terms.den)};
}

int compare_quotients(const Ray& ray, const Plane& a, const Plane& b) {
  const RayPlaneValues<mpq_class> ta = exact_terms(ray, a), tb = exact_terms(ray, b);
  return sgn(mpq_class(ta.num * tb.den - tb.num * ta.den));
}

std::vector<std::uint32_t> distinct_planes(std::span<const Plane> planes) {
  std::map<std::string, std::uint32_t> first_of_key;
  std::vector<std::uint32_t> distinct;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const Plane& p = planes[k];
    const mpq_class n[3] = {rational_from_double(p.normal.x), rational_from_double(p.normal.y),
                            rational_from_double(p.normal.z)};
    const mpq_class offset = n[0] * rational_from_double(p.point.x) + n[1] * rational_from_double(p.point.y) +
                             n[2] * rational_from_double(p.point.z);
    const mpq_class& lead = sgn(n[0]) != 0 ? n[0] : (sgn(n[1]) != 0 ? n[1] : n[2]);  // nonzero: the plane is valid
    std::string key;
    for (const mpq_class& c : {mpq_class(n[0] / lead), mpq_class(n[1] / lead), mpq_class(n[2] / lead), mpq_class(offset / lead)})
      key += c.get_str(16) + ' ';
    if (first_of_key.emplace(std::move(key), static_cast<std::uint32_t>(k)).second)
      distinct.push_back(static_cast<std::uint32_t>(k));
  }
  return distinct;
}

std::optional<std::size_t> nearest_plane(const Ray& ray, std::span<const Plane> planes) {
  std::optional<std::size_t> best;
  mpq_class best_t;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const RayPlaneValues<mpq_class> terms = exact_terms(ray, planes[k]);
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
