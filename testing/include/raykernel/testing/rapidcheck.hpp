// RapidCheck generators of hard ray–plane queries, for RC_GTEST_PROP properties of raykernel and of ray code
// tested against it. Header-only: include it after <rapidcheck.h> is available and link rapidcheck.
//
//   RC_GTEST_PROP(MyRayCode, MatchesRaykernel, ()) {
//     const auto q = *raykernel::testing::gen_hard_query();
//     ...
//   }
//
// Every random word a construction draws is a separate RapidCheck value, uniform over all 64-bit words and
// shrinking toward 0, so a failing query shrinks toward a simpler one of the same kind.
#pragma once

#include <raykernel/testing/hard_queries.hpp>

#include <rapidcheck.h>

#include <cstdint>
#include <cstdio>
#include <limits>
#include <ostream>

namespace raykernel::testing {

// A query of one kind.
inline rc::Gen<Query> gen_query(QueryKind kind) {
  return rc::gen::exec([kind] {
    const BitSource bits = [] {
      return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max());
    };
    return make_query(kind, bits);
  });
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

}  // namespace raykernel::testing

namespace rc {
template <>
struct Arbitrary<raykernel::testing::QueryKind> {
  static Gen<raykernel::testing::QueryKind> arbitrary() { return raykernel::testing::gen_query_kind(); }
};
template <>
struct Arbitrary<raykernel::testing::KindedQuery> {
  static Gen<raykernel::testing::KindedQuery> arbitrary() { return raykernel::testing::gen_hard_query(); }
};
}  // namespace rc

// So that RapidCheck prints a counterexample exactly: every component as a hexadecimal float.
namespace raykernel::testing {
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
}  // namespace raykernel::testing
