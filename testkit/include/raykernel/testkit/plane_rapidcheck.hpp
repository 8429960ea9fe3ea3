// RapidCheck generators of hard ray–plane queries, for RC_GTEST_PROP properties of raykernel and of ray code
// tested against it. Header-only: it needs <rapidcheck.h> on the include path and the `rapidcheck` library
// (with the installed package: find_package(raykernel CONFIG REQUIRED COMPONENTS testing) finds it, then
// target_link_libraries(my_test PRIVATE raykernel::testkit rapidcheck)).
//
//   RC_GTEST_PROP(MyRayCode, MatchesRaykernel, (const raykernel::testkit::KindedQuery& k)) {
//     RC_TAG(raykernel::testkit::to_string(k.kind));
//     RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(k.query, my_intersect(k.query.ray, k.query.plane), 4);
//   }
//
//   RC_GTEST_PROP(MyNearestHit, OrdersNearTies, (const raykernel::testkit::PlanePair& pp)) {
//     RC_ASSERT(my_nearest(pp.ray, pp.planes) == pp.nearest());
//   }
//
// Generators: gen_query(kind), gen_hard_query() (a kind drawn uniformly, or from a list), and
// gen_plane_pair_near_tie() (two planes tying exactly along the ray, or less than an ulp of t apart:
// plane_pairs.hpp). `Arbitrary` is specialized for KindedQuery, QueryKind and PlanePair, so they can be
// property parameters. Every random word a construction draws is a separate RapidCheck value, uniform over
// all 64-bit words and shrinking toward 0, so a failing input shrinks toward a simpler one of the same
// kind; counterexamples print every component as a hexadecimal float (exact, and readable by strtod and by
// `raykernel classify`).
#pragma once

#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/plane_pairs.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>

#include <rapidcheck.h>

#include <cstdint>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <ostream>
#include <vector>

namespace raykernel::testkit {

// A BitSource for use inside rc::gen::exec: each word is a separate RapidCheck value, uniform and shrinking
// toward 0.
inline BitSource rc_bit_source() {
  return [] { return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max()); };
}

// A query of one kind.
inline rc::Gen<Query> gen_query(QueryKind kind) {
  return rc::gen::exec([kind] { return make_query(kind, rc_bit_source()); });
}

// One of the kinds, uniformly.
inline rc::Gen<QueryKind> gen_query_kind() { return rc::gen::elementOf(all_query_kinds); }

// A query of a uniformly chosen kind, with the kind (for RC_TAG).
struct KindedQuery {
  QueryKind kind;
  Query query;
};
inline rc::Gen<KindedQuery> gen_hard_query() {
  return rc::gen::mapcat(gen_query_kind(), [](QueryKind kind) {
    return rc::gen::map(gen_query(kind), [kind](Query q) { return KindedQuery{kind, q}; });
  });
}
// A query of a kind drawn uniformly from `kinds` (not empty), e.g. {QueryKind::near_parallel,
// QueryKind::subnormal} to aim at one weakness.
inline rc::Gen<KindedQuery> gen_hard_query(std::initializer_list<QueryKind> kinds) {
  return rc::gen::mapcat(rc::gen::elementOf(std::vector<QueryKind>(kinds)), [](QueryKind kind) {
    return rc::gen::map(gen_query(kind), [kind](Query q) { return KindedQuery{kind, q}; });
  });
}

// One ray and two planes whose exact t tie or differ by less than an ulp (plane_pairs.hpp): for
// nearest-hit code, check the winner against PlanePair::nearest().
inline rc::Gen<PlanePair> gen_plane_pair_near_tie() {
  return rc::gen::exec([] { return make_plane_pair_near_tie(rc_bit_source()); });
}
inline rc::Gen<PlanePair> gen_plane_pair_near_tie(PlaneTieKind kind) {
  return rc::gen::exec([kind] { return make_plane_pair_near_tie(kind, rc_bit_source()); });
}

}  // namespace raykernel::testkit

// Fails the current RapidCheck case unless `got` (an Intersection) is the exact answer to `query` with t
// within `max_t_ulps` ulps (reference_check.hpp); the failure message is the check's report (the query in
// hexadecimal floats, a replay command, expected and got, the exact t as P/Q, the ulp distance).
#define RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(query, got, max_t_ulps)                                       \
  do {                                                                                                     \
    const ::raykernel::testkit::ReferenceCheck raykernel_rc_check_ =                                       \
        ::raykernel::testkit::check_against_reference((query), (got), (max_t_ulps));                       \
    if (!raykernel_rc_check_.passed()) RC_FAIL(raykernel_rc_check_.report());                              \
  } while (false)

namespace rc {
template <>
struct Arbitrary<raykernel::testkit::QueryKind> {
  static Gen<raykernel::testkit::QueryKind> arbitrary() { return raykernel::testkit::gen_query_kind(); }
};
template <>
struct Arbitrary<raykernel::testkit::KindedQuery> {
  static Gen<raykernel::testkit::KindedQuery> arbitrary() { return raykernel::testkit::gen_hard_query(); }
};
template <>
struct Arbitrary<raykernel::testkit::PlanePair> {
  static Gen<raykernel::testkit::PlanePair> arbitrary() { return raykernel::testkit::gen_plane_pair_near_tie(); }
};
}  // namespace rc

// So that RapidCheck prints a counterexample exactly: every component as a hexadecimal float.
namespace raykernel::testkit {
inline void showValue(const Query& q, std::ostream& os) {
  auto v = [&os](const char* name, const Vec3& a) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s=(%a, %a, %a) ", name, a.x, a.y, a.z);
    os << buf;
  };
  v("o", q.ray.origin);
  v("d", q.ray.direction);
  v("p", q.plane.point);
  v("n", q.plane.normal);
}
inline void showValue(const KindedQuery& k, std::ostream& os) {
  os << to_string(k.kind) << ": ";
  showValue(k.query, os);
}
inline void showValue(QueryKind k, std::ostream& os) { os << to_string(k); }
inline void showValue(const PlanePair& pp, std::ostream& os) {
  auto v = [&os](const char* name, const Vec3& a) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s=(%a, %a, %a) ", name, a.x, a.y, a.z);
    os << buf;
  };
  os << to_string(pp.kind) << " (order " << pp.order << ", nearest " << pp.nearest() << "): ";
  v("o", pp.ray.origin);
  v("d", pp.ray.direction);
  v("p0", pp.planes[0].point);
  v("n0", pp.planes[0].normal);
  v("p1", pp.planes[1].point);
  v("n1", pp.planes[1].normal);
}
}  // namespace raykernel::testkit
