// RapidCheck generators of hard ray–triangle queries (triangle_queries.hpp), for RC_GTEST_PROP properties of
// raykernel and of ray–triangle code tested against it. Header-only; needs <rapidcheck.h> and `rapidcheck`.
//
//   RC_GTEST_PROP(MyTriangleCode, MatchesRaykernel, (const raykernel::testkit::KindedTriangleQuery& k)) {
//     RC_TAG(raykernel::testkit::to_string(k.kind));
//     RAYKERNEL_RC_ASSERT_TRIANGLE_MATCHES_REFERENCE(k.query, my_intersect(k.query.ray, k.query.triangle),
//                                                   raykernel::TriangleRule::closed, 4);
//   }
//
// Every random word a construction draws is a separate RapidCheck value (rc_bit_source), so failures shrink
// toward simpler queries of the same kind; counterexamples print every component as a hexadecimal float.
#pragma once

#include <raykernel/testkit/plane_rapidcheck.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/testkit/triangle_reference_check.hpp>

#include <rapidcheck.h>

#include <initializer_list>
#include <ostream>
#include <vector>

namespace raykernel::testkit {

inline rc::Gen<TriangleQuery> gen_triangle_query(TriangleQueryKind kind) {
  return rc::gen::exec([kind] { return make_triangle_query(kind, rc_bit_source()); });
}

inline rc::Gen<TriangleQueryKind> gen_triangle_query_kind() { return rc::gen::elementOf(all_triangle_query_kinds); }

struct KindedTriangleQuery {
  TriangleQueryKind kind;
  TriangleQuery query;
};

// A query of a uniformly chosen kind, or of a kind drawn from `kinds` (not empty).
inline rc::Gen<KindedTriangleQuery> gen_hard_triangle_query() {
  return rc::gen::mapcat(gen_triangle_query_kind(), [](TriangleQueryKind kind) {
    return rc::gen::map(gen_triangle_query(kind), [kind](TriangleQuery q) { return KindedTriangleQuery{kind, q}; });
  });
}
inline rc::Gen<KindedTriangleQuery> gen_hard_triangle_query(std::initializer_list<TriangleQueryKind> kinds) {
  return rc::gen::mapcat(rc::gen::elementOf(std::vector<TriangleQueryKind>(kinds)), [](TriangleQueryKind kind) {
    return rc::gen::map(gen_triangle_query(kind), [kind](TriangleQuery q) { return KindedTriangleQuery{kind, q}; });
  });
}

inline void showValue(const TriangleQuery& q, std::ostream& os) { os << to_string(q); }
inline void showValue(const KindedTriangleQuery& k, std::ostream& os) {
  os << to_string(k.kind) << ": " << to_string(k.query);
}
inline void showValue(TriangleQueryKind k, std::ostream& os) { os << to_string(k); }

}  // namespace raykernel::testkit

// Fails the current RapidCheck case unless `got` (a TriangleIntersection) is the exact answer under `rule`
// with t and the coordinates within `max_ulps` (triangle_reference_check.hpp); the message is the report.
#define RAYKERNEL_RC_ASSERT_TRIANGLE_MATCHES_REFERENCE(query, got, rule, max_ulps)                          \
  do {                                                                                                     \
    const ::raykernel::testkit::TriangleReferenceCheck raykernel_rc_triangle_check_ =                      \
        ::raykernel::testkit::check_against_reference((query), (got), (rule), (max_ulps));                 \
    if (!raykernel_rc_triangle_check_.passed()) RC_FAIL(raykernel_rc_triangle_check_.report());            \
  } while (false)

namespace rc {
template <>
struct Arbitrary<raykernel::testkit::TriangleQueryKind> {
  static Gen<raykernel::testkit::TriangleQueryKind> arbitrary() { return raykernel::testkit::gen_triangle_query_kind(); }
};
template <>
struct Arbitrary<raykernel::testkit::KindedTriangleQuery> {
  static Gen<raykernel::testkit::KindedTriangleQuery> arbitrary() {
    return raykernel::testkit::gen_hard_triangle_query();
  }
};
}  // namespace rc
