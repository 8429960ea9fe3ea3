// The exact ray–sphere stage: ray_sphere_formula.hpp instantiated with GMP's mpq_class (core/exact_value.hpp),
// the roots U ∓ √V rounded once by core/root_rounding.hpp.
#include "sphere/exact_sphere.hpp"
#include "core/root_rounding.hpp"

#include "core/binary64_rounding.hpp"
#include "core/exact_value.hpp"
#include "sphere/ray_sphere_formula.hpp"

#include <gmpxx.h>
#include <mpfr.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>

namespace raykernel::detail::exact {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

RaySphereTerms<Exact> exact_terms(const Ray& ray, const Sphere& sphere) {
  return ray_sphere_terms<Exact>(ray, sphere, lift, difference);
}

double round_root(const mpq_class& u, const mpq_class& v, int root) {
  return round_root(u, v, root, binary64_format, MPFR_RNDN);
}

struct Decided {
  SphereClassification classification;
  mpq_class u, v;  // meaningful unless miss
};

Decided decide(const Ray& ray, const Sphere& sphere) {
  const RaySphereTerms<Exact> t = exact_terms(ray, sphere);
  Decided r{{sphere_origin(sgn(t.c)), sphere_relation(sgn(t.d))}, {}, {}};
  if (r.classification.relation == SphereRelation::miss) return r;
  r.u = -t.b.q / t.a.q;
  r.v = t.d.q / (t.a.q * t.a.q);
  return r;
}

}  // namespace

SphereClassification classify_sphere(const Ray& ray, const Sphere& sphere) {
  const RaySphereTerms<Exact> t = exact_terms(ray, sphere);
  return {sphere_origin(sgn(t.c)), sphere_relation(sgn(t.d))};
}

SphereIntersection intersect_sphere(const Ray& ray, const Sphere& sphere) {
  const Decided d = decide(ray, sphere);
  SphereIntersection r{d.classification.origin, d.classification.relation, not_a_number, not_a_number};
  if (r.relation == SphereRelation::miss) return r;
  r.t1 = round_root(d.u, d.v, -1);
  r.t2 = r.relation == SphereRelation::tangent ? r.t1 : round_root(d.u, d.v, +1);
  return r;
}

ExactSphereIntersection intersect_sphere_rational(const Ray& ray, const Sphere& sphere) {
  const Decided d = decide(ray, sphere);
  ExactSphereIntersection r{d.classification.origin, d.classification.relation, std::nullopt, std::nullopt};
  if (r.relation == SphereRelation::miss) return r;
  r.u = to_public(d.u);
  r.v = to_public(d.v);
  return r;
}

int root_side_of_midpoint(const Ray& ray, const Sphere& sphere, int root, double x, double y) {
  const RaySphereTerms<Exact> t = exact_terms(ray, sphere);
  const mpq_class m = (rational_from_double(x) + rational_from_double(y)) / 2;
  const mpq_class q = t.a.q * m * m + 2 * t.b.q * m + t.c.q, slope = t.a.q * m + t.b.q;
  return root_side_of(root, sgn(q), sgn(slope));
}

bool segment_meets_sphere(const Vec3& p, const Vec3& q, const Sphere& sphere) {
  const SegmentSphereTerms<Exact> t = segment_sphere_terms<Exact>(p, q, sphere, lift, difference);
  return segment_root_inside(sgn(t.d.q), sgn(t.c_p.q), sgn(t.b_p.q), sgn(t.c_q.q), sgn(t.b_q.q));
}

}  // namespace raykernel::detail::exact
