// The hard-query constructors keep their promises: checked with the test's own exact arithmetic
// (support/oracle.hpp), because every property test and benchmark relies on them.
#include "support/oracle.hpp"

#include <raykernel/testkit/plane_queries.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace raykernel {
namespace {

using testkit::QueryKind;

bool all_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool nonzero(const Vec3& v) { return v.x != 0 || v.y != 0 || v.z != 0; }
double max_abs(const Vec3& v) { return std::fmax(std::fabs(v.x), std::fmax(std::fabs(v.y), std::fabs(v.z))); }

// Whether q·2^-e, for the e that makes it lie in [2^53, 2^54), is an odd integer: a rounding midpoint.
bool is_midpoint(mpq_class q) {
  q = abs(q);
  if (q == 0) return false;
  while (q < mpq_class(mpz_class(1) << 53)) q *= 2;
  while (q >= mpq_class(mpz_class(1) << 54)) q /= 2;
  return q.get_den() == 1 && mpz_odd_p(q.get_num_mpz_t());
}

void check_promise(QueryKind kind, const testkit::Query& q, int i) {
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + " #" + std::to_string(i));
  for (const Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal}) ASSERT_TRUE(all_finite(v));
  ASSERT_TRUE(nonzero(q.ray.direction));
  ASSERT_TRUE(nonzero(q.plane.normal));
  const test_support::ExactTerms e = test_support::exact_terms(q.ray, q.plane);
  switch (kind) {
    case QueryKind::exact_parallel: EXPECT_TRUE(e.den == 0 && e.num != 0); break;
    case QueryKind::exact_in_plane: EXPECT_TRUE(e.den == 0 && e.num == 0); break;
    case QueryKind::origin_on_plane: EXPECT_TRUE(e.num == 0); break;
    case QueryKind::rounding_tie: ASSERT_NE(e.den, 0); EXPECT_TRUE(is_midpoint(e.num / e.den)); break;
    case QueryKind::above_power_of_two:
      ASSERT_NE(e.den, 0);
      EXPECT_TRUE(test_support::just_above_power_of_two(e.num / e.den));
      break;
    case QueryKind::near_tie: {
      ASSERT_NE(e.den, 0);
      const mpq_class t = e.num / e.den;
      EXPECT_FALSE(is_midpoint(t));
      // Within 2^-20 ulp of a midpoint: t's distance to the nearest midpoint, in units of its ulp.
      const double rounded = test_support::round_by_integer_division(t);
      const double next = std::nextafter(rounded, t > mpq_class(rounded) ? HUGE_VAL : -HUGE_VAL);
      const mpq_class mid = (mpq_class(rounded) + mpq_class(next)) / 2;
      const mpq_class ulp = abs(mpq_class(next) - mpq_class(rounded));
      EXPECT_LE(abs(t - mid) / ulp, mpq_class(1, 1 << 20));
      break;
    }
    case QueryKind::near_parallel: {
      // |d·n| small relative to |d||n| (the product magnitudes): at most 2^-40 of Σ|d_i n_i|.
      const Vec3 &d = q.ray.direction, &n = q.plane.normal;
      const mpq_class mag = abs(mpq_class(d.x) * n.x) + abs(mpq_class(d.y) * n.y) + abs(mpq_class(d.z) * n.z);
      EXPECT_LE(abs(e.den), mag / mpq_class(mpz_class(1) << 40));
      break;
    }
    case QueryKind::near_coplanar: {
      const Vec3 &o = q.ray.origin, &p = q.plane.point, &n = q.plane.normal;
      const mpq_class mag = abs((mpq_class(p.x) - o.x) * n.x) + abs((mpq_class(p.y) - o.y) * n.y) +
                            abs((mpq_class(p.z) - o.z) * n.z) + abs(mpq_class(p.x) * n.x) + abs(mpq_class(p.y) * n.y) +
                            abs(mpq_class(p.z) * n.z);
      EXPECT_LE(abs(e.num), mag / mpq_class(mpz_class(1) << 40));
      break;
    }
    case QueryKind::subnormal:
      for (const Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal})
        EXPECT_LE(max_abs(v), 0x1p-399);
      break;
    case QueryKind::huge_products:
      for (const Vec3& v : {q.ray.origin, q.ray.direction, q.plane.point, q.plane.normal}) EXPECT_GE(max_abs(v), 0x1p400);
      break;
    case QueryKind::t_overflow:
      ASSERT_NE(e.den, 0);
      EXPECT_GE(abs(e.num / e.den), mpq_class(mpz_class(1) << 800));
      break;
    case QueryKind::t_underflow:
      if (e.num != 0 && e.den != 0) {
        EXPECT_LE(abs(e.num / e.den), mpq_class(1, mpz_class(1) << 900));
      }
      break;
    case QueryKind::random:
    case QueryKind::wide_exponents: break;
  }
}

TEST(HardQueries, EveryKindKeepsItsPromise) {
  testkit::SplitMix64 rng(42);
  const testkit::BitSource bits = [&rng] { return rng(); };
  for (QueryKind kind : testkit::all_query_kinds)
    for (int i = 0; i < 500; ++i) check_promise(kind, testkit::make_query(kind, bits), i);
}

TEST(HardQueries, AllZeroWordsStillGiveValidQueries) {
  // What a shrinker tries first.
  const testkit::BitSource zeros = [] { return std::uint64_t{0}; };
  for (QueryKind kind : testkit::all_query_kinds) {
    const testkit::Query q = testkit::make_query(kind, zeros);
    EXPECT_FALSE(validate(q.ray, q.plane).has_value()) << testkit::to_string(kind);
  }
}

TEST(HardQueries, DeterministicInTheWordsDrawn) {
  for (QueryKind kind : testkit::all_query_kinds) {
    testkit::SplitMix64 a(7), b(7);
    const testkit::Query qa = testkit::make_query(kind, [&a] { return a(); });
    const testkit::Query qb = testkit::make_query(kind, [&b] { return b(); });
    EXPECT_EQ(std::memcmp(&qa, &qb, sizeof qa), 0) << testkit::to_string(kind);
  }
}

}  // namespace
}  // namespace raykernel
