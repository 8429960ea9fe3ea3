// The exact ray–sphere stage: ray_sphere_formula.hpp instantiated with GMP's mpq_class (core/exact_value.hpp),
// the roots rounded by MPFR (core/binary64_rounding.hpp).
//
// A root U ∓ √V is rational exactly when V is the square of a rational (its numerator and denominator, in lowest
// terms, are perfect squares); then it is rounded as a rational, ties included. Otherwise it is irrational, so
// neither a double nor a midpoint of two doubles: an enclosure [lo, hi] of it, computed by MPFR with directed
// roundings, whose two ends round to the same double gives RN(root) (rounding to nearest is monotonic), and
// doubling the precision until they do terminates.
#include "sphere/exact_sphere.hpp"
#include "sphere/exact_root.hpp"

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

// √v when v ≥ 0 is the square of a rational.
std::optional<mpq_class> rational_sqrt(const mpq_class& v) {
  if (!mpz_perfect_square_p(v.get_num_mpz_t()) || !mpz_perfect_square_p(v.get_den_mpz_t())) return std::nullopt;
  mpz_class n, d;
  mpz_sqrt(n.get_mpz_t(), v.get_num_mpz_t());
  mpz_sqrt(d.get_mpz_t(), v.get_den_mpz_t());
  return mpq_class(n, d);  // lowest terms already: the roots of coprime squares are coprime
}

// An MPFR number of a given precision, freed on scope exit.
class Big {
 public:
  explicit Big(mpfr_prec_t precision) { mpfr_init2(x_, precision); }
  ~Big() { mpfr_clear(x_); }
  Big(const Big&) = delete;
  Big& operator=(const Big&) = delete;
  mpfr_ptr get() { return x_; }

 private:
  mpfr_t x_;
};

bool same_double(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// U + root·√V, V > 0 not the square of a rational (the value is irrational), rounded once to the format in the
// mode (MPFR_RNDN, MPFR_RNDU, MPFR_RNDD).
double round_irrational_root(const mpq_class& u, const mpq_class& v, int root, const BinaryFormat& format,
                             mpfr_rnd_t mode) {
  for (mpfr_prec_t precision = 128; precision <= (mpfr_prec_t{1} << 24); precision *= 2) {
    Big u_lo(precision), u_hi(precision), v_lo(precision), v_hi(precision), s_lo(precision), s_hi(precision),
        lo(precision), hi(precision);
    mpfr_set_q(u_lo.get(), u.get_mpq_t(), MPFR_RNDD);
    mpfr_set_q(u_hi.get(), u.get_mpq_t(), MPFR_RNDU);
    mpfr_set_q(v_lo.get(), v.get_mpq_t(), MPFR_RNDD);
    mpfr_set_q(v_hi.get(), v.get_mpq_t(), MPFR_RNDU);
    mpfr_sqrt(s_lo.get(), v_lo.get(), MPFR_RNDD);  // s_lo ≤ √V ≤ s_hi
    mpfr_sqrt(s_hi.get(), v_hi.get(), MPFR_RNDU);
    if (root < 0) {
      mpfr_sub(lo.get(), u_lo.get(), s_hi.get(), MPFR_RNDD);
      mpfr_sub(hi.get(), u_hi.get(), s_lo.get(), MPFR_RNDU);
    } else {
      mpfr_add(lo.get(), u_lo.get(), s_lo.get(), MPFR_RNDD);
      mpfr_add(hi.get(), u_hi.get(), s_hi.get(), MPFR_RNDU);
    }
    // lo ≤ root ≤ hi, both finite (the default exponent range holds every value here): rounding is monotonic,
    // so when both ends round to the same value, so does the root.
    mpq_class q_lo, q_hi;
    mpfr_get_q(q_lo.get_mpq_t(), lo.get());
    mpfr_get_q(q_hi.get_mpq_t(), hi.get());
    const double a = round_rational(q_lo, format, mode), b = round_rational(q_hi, format, mode);
    if (same_double(a, b)) return a;
  }
  throw std::logic_error("raykernel: exact sphere root: no rounding decided at 2^24 bits");  // unreachable
}

}  // namespace

double round_root(const mpq_class& u, const mpq_class& v, int root, const BinaryFormat& format, mpfr_rnd_t mode,
                  bool* exact) {
  if (const std::optional<mpq_class> s = rational_sqrt(v))
    return round_rational(root < 0 ? mpq_class(u - *s) : mpq_class(u + *s), format, mode, exact);  // exact 0: +0
  if (exact != nullptr) *exact = false;
  return round_irrational_root(u, v, root, format, mode);
}

namespace {

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
