// RapidCheck properties of the certified path.
//
//  * Agreement: `intersect` == `intersect_exact` (relation and the bits of t) on generated hard queries.
//    The exact path is the oracle; the generators (raykernel/testkit/plane_rapidcheck.hpp) aim at near-parallel
//    rays, origins within ulps of the plane, exact degeneracies, ties, subnormals and huge exponents.
//  * Metamorphic relations, each an exact consequence of docs/contract.md §1: scaling n or d by a power of two,
//    negating n or d, moving the origin along d by an exactly representable step.
//
// The case count comes from RC_PARAMS (tests/CMakeLists.txt sets max_success; the `long` ctest runs the
// agreement property 10^6 times). RapidCheck prints the seed it used ("Using configuration: seed=...");
// RC_PARAMS="seed=N" reproduces a run, and a failure prints its own "reproduce" string.
#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace raykernel {
namespace {

using test_support::same_answer;
using testkit::KindedQuery;
using testkit::Query;

std::string tag_of(const TracedIntersection& r) {
  return std::string(to_string(r.intersection.relation)) + "/" + std::string(to_string(r.relation_stage));
}

// x·2^k if that is exact (no overflow, no loss of bits), else nothing.
std::optional<Vec3> scaled_exactly(const Vec3& v, int k) {
  const Vec3 s{std::ldexp(v.x, k), std::ldexp(v.y, k), std::ldexp(v.z, k)};
  const bool exact = std::ldexp(s.x, -k) == v.x && std::ldexp(s.y, -k) == v.y && std::ldexp(s.z, -k) == v.z &&
                     std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.z);
  if (!exact) return std::nullopt;
  return s;
}

RC_GTEST_PROP(Certified, AgreesWithExactOnHardQueries, (const KindedQuery& k)) {
  const Query& q = k.query;
  const TracedIntersection certified = intersect_traced(q.ray, q.plane);
  const Intersection exact = intersect_exact(q.ray, q.plane);
  RC_TAG(testkit::to_string(k.kind));
  RC_CLASSIFY(true, tag_of(certified));
  RC_ASSERT(same_answer(certified.intersection, exact));
}

RC_GTEST_PROP(Certified, ExactPathAgreesWithIndependentOracle, (const KindedQuery& k)) {
  // The reference itself against the test's own rationals and integer-division rounding.
  RC_ASSERT(same_answer(intersect_exact(k.query.ray, k.query.plane), test_support::contract_answer(k.query.ray, k.query.plane)));
}

RC_GTEST_PROP(Metamorphic, ScalingTheNormalByAPowerOfTwoChangesNothing, (const KindedQuery& k)) {
  const int power = *rc::gen::inRange(-60, 61);
  Query q = k.query;
  const auto n = scaled_exactly(q.plane.normal, power);
  RC_PRE(n.has_value());
  q.plane.normal = *n;
  RC_ASSERT(same_answer(intersect(q.ray, q.plane), intersect(k.query.ray, k.query.plane)));
}

RC_GTEST_PROP(Metamorphic, ScalingTheDirectionByAPowerOfTwoScalesT, (const KindedQuery& k)) {
  // num/den becomes (num/den)·2^-k: the relation is unchanged, and t scales exactly unless the scaled or
  // unscaled t leaves the normal range (then rounding differs, and the exact path decides).
  const int power = *rc::gen::inRange(-60, 61);
  Query q = k.query;
  const auto d = scaled_exactly(q.ray.direction, power);
  RC_PRE(d.has_value());
  q.ray.direction = *d;
  const Intersection before = intersect(k.query.ray, k.query.plane);
  const Intersection after = intersect(q.ray, q.plane);
  RC_ASSERT(after.relation == before.relation);
  if (before.relation == Relation::hit || before.relation == Relation::behind) {
    // Rounding commutes with scaling by 2^-k when the exact t and the scaled one are both strictly inside
    // the normal range; |RN(t)| strictly between 2^-1022 and the largest double guarantees that.
    const double expected = std::ldexp(before.t, -power);
    auto interior = [](double x) { return std::fabs(x) > 0x1p-1022 && std::fabs(x) < std::numeric_limits<double>::max(); };
    if (interior(before.t) && interior(expected)) RC_ASSERT(test_support::same_bits(after.t, expected));
    else RC_ASSERT(same_answer(after, intersect_exact(q.ray, q.plane)));
  }
}

RC_GTEST_PROP(Metamorphic, NegatingTheNormalChangesNothing, (const KindedQuery& k)) {
  Query q = k.query;
  q.plane.normal = {-q.plane.normal.x, -q.plane.normal.y, -q.plane.normal.z};
  RC_ASSERT(same_answer(intersect(q.ray, q.plane), intersect(k.query.ray, k.query.plane)));
}

RC_GTEST_PROP(Metamorphic, ReversingTheDirectionNegatesT, (const KindedQuery& k)) {
  Query q = k.query;
  q.ray.direction = {-q.ray.direction.x, -q.ray.direction.y, -q.ray.direction.z};
  const Intersection before = intersect(k.query.ray, k.query.plane);
  const Intersection after = intersect(q.ray, q.plane);
  switch (before.relation) {
    case Relation::parallel:
    case Relation::in_plane: RC_ASSERT(after.relation == before.relation); break;
    case Relation::hit:
    case Relation::behind:
      if (before.t == 0 && !std::signbit(before.t) && before.relation == Relation::hit) {
        // t = +0 is either the origin on the plane (stays a hit at +0) or a tiny positive t (becomes
        // behind at −0); the exact num tells which.
        const bool on_plane = test_support::exact_terms(q.ray, q.plane).num == 0;
        RC_ASSERT(after.relation == (on_plane ? Relation::hit : Relation::behind));
        RC_ASSERT(test_support::same_bits(after.t, on_plane ? 0.0 : -0.0));
      } else {
        RC_ASSERT(after.relation == (before.relation == Relation::hit ? Relation::behind : Relation::hit));
        RC_ASSERT(test_support::same_bits(after.t, -before.t));
      }
      break;
  }
}

// x with its significand cut to 26 bits (toward zero): a double whose sums with other such doubles of
// nearby exponents are exact.
double truncate_to_26_bits(double x) {
  if (x == 0 || !std::isnormal(x)) return x;
  int e;
  (void)std::frexp(x, &e);
  return std::ldexp(std::trunc(std::ldexp(x, 26 - e)), e - 26);
}

RC_GTEST_PROP(Metamorphic, MovingTheOriginAlongTheRayShiftsT, (const KindedQuery& k)) {
  // o' = o + s·d with s = ±2^j. For this to be an exact move, o and d are first cut to 26-bit significands
  // and j is chosen so that s·d lands near o's magnitude; the few cases where o + s·d is still inexact are
  // discarded. Then the exact t' is t − s, so the certified answer must be RN(t − s), hit or behind by sign.
  Query q = k.query;
  Vec3& o = q.ray.origin;
  Vec3& d = q.ray.direction;
  for (double* c : {&o.x, &o.y, &o.z, &d.x, &d.y, &d.z}) *c = truncate_to_26_bits(*c);
  RC_PRE(d.x != 0 || d.y != 0 || d.z != 0);
  int eo, ed;
  (void)std::frexp(std::fmax(std::fabs(o.x), std::fmax(std::fabs(o.y), std::fabs(o.z))), &eo);
  (void)std::frexp(std::fmax(std::fabs(d.x), std::fmax(std::fabs(d.y), std::fabs(d.z))), &ed);
  const int j = std::clamp(eo - ed + *rc::gen::inRange(-12, 13), -1000, 1000);
  const double s = *rc::gen::element(1.0, -1.0) * std::ldexp(1.0, j);
  RC_PRE(s != 0 && std::isfinite(s));
  Query moved = q;
  double* m[3] = {&moved.ray.origin.x, &moved.ray.origin.y, &moved.ray.origin.z};
  const double oc[3] = {o.x, o.y, o.z}, dc[3] = {d.x, d.y, d.z};
  for (int i = 0; i < 3; ++i) {
    *m[i] = oc[i] + s * dc[i];
    // Computed first: RapidCheck's macros decompose `a && b` and would lose its short circuit.
    const bool exact_move =
        std::isfinite(*m[i]) && mpq_class(*m[i]) == mpq_class(oc[i]) + mpq_class(s) * mpq_class(dc[i]);
    RC_PRE(exact_move);
  }
  const test_support::ExactTerms before = test_support::exact_terms(q.ray, q.plane);
  RC_PRE(before.den != 0);
  const mpq_class t_moved = before.num / before.den - mpq_class(s);
  const Intersection after = intersect(moved.ray, moved.plane);
  RC_ASSERT(after.relation == (t_moved >= 0 ? Relation::hit : Relation::behind));
  RC_ASSERT(test_support::same_bits(after.t, test_support::round_by_integer_division(t_moved)));
  RC_TAG(t_moved >= 0 ? "moved: hit" : "moved: behind");
}

}  // namespace
}  // namespace raykernel
