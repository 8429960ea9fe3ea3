// The exact stage: num and den as CGAL::Exact_rational (GMP's mpq_class), t rounded by MPFR.
//
// Two details decide correctness here:
//  * Doubles are converted to rationals from their bit patterns (sign, exponent, significand), never
//    through floating-point operations, so the conversion is exact whatever the FP environment (GMP's
//    mpq_set_d goes through FP arithmetic, which flush-to-zero modes would corrupt).
//  * t is rounded with MPFR in an emulated binary64 (core/binary64_rounding.hpp, the one rounding every
//    exact t and coordinate goes through): one correct rounding to nearest-even with gradual underflow and
//    overflow to ±inf. mpq_get_d and CGAL::to_double truncate and are not used.
#include "plane/exact_plane.hpp"

#include "core/binary64_rounding.hpp"
#include "core/exact_value.hpp"
#include "core/rational_from_double.hpp"
#include "core/fp_environment.hpp"
#include "plane/ray_plane_formula.hpp"

#include <CGAL/Exact_rational.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace raykernel::detail::exact {
namespace {

using Rational = CGAL::Exact_rational;
static_assert(std::is_same_v<Rational, mpq_class>,
              "raykernel expects CGAL::Exact_rational to be GMP's mpq_class (CGAL with GMP and gmpxx)");

// Doubles become rationals from their bits: rational_from_double (CGAL::Exact_rational is mpq_class).
Rational to_rational(double x) { return rational_from_double(x); }

RayPlaneValues<Rational> exact_terms(const Ray& ray, const Plane& plane) {
  return ray_plane_values<Rational>(ray, plane, to_rational);
}

Intersection decide(const RayPlaneValues<Rational>& terms, Rational* exact_t) {
  const Relation relation = relation_from_signs(CGAL::sign(terms.num), CGAL::sign(terms.den));
  if (relation == Relation::parallel || relation == Relation::in_plane)
    return {relation, std::numeric_limits<double>::quiet_NaN()};
  Rational t = terms.num / terms.den;  // 0/den is the canonical 0, which rounds to +0
  const double rounded = round_rational_to_nearest_even(t);
  if (exact_t != nullptr) *exact_t = std::move(t);
  return {relation, rounded};
}

}  // namespace

Intersection intersect(const Ray& ray, const Plane& plane) { return decide(exact_terms(ray, plane), nullptr); }

ExactIntersection intersect_rational(const Ray& ray, const Plane& plane) {
  const RayPlaneValues<Rational> terms = exact_terms(ray, plane);
  Rational t;
  const Intersection result = decide(terms, &t);
  ExactIntersection exact{result, to_public(terms.num), to_public(terms.den), std::nullopt};
  if (result.relation == Relation::hit || result.relation == Relation::behind) exact.t = to_public(t);
  return exact;
}

}  // namespace raykernel::detail::exact

namespace raykernel {

double round_rational_to_double(std::string_view numerator, std::string_view denominator) {
  return detail::in_default_fp_environment([&] {
  mpz_class num, den;
  if (num.set_str(std::string(numerator), 10) != 0 || den.set_str(std::string(denominator), 10) != 0)
    throw std::invalid_argument("round_rational_to_double: not a decimal integer");
  if (den == 0) throw std::invalid_argument("round_rational_to_double: zero denominator");
  mpq_class q(num, den);
  q.canonicalize();
  return detail::exact::round_rational_to_nearest_even(q);
  });
}

}  // namespace raykernel
