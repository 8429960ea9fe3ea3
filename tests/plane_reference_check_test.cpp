// raykernel::testkit's user-facing tools: the ulp distance, the reference check and its report, the near-tie
// plane pairs and their RapidCheck generators. Exact claims are checked with the test's own rationals
// (support/oracle.hpp), not with the kernel.
#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit.hpp>
#include <raykernel/testkit/plane_rapidcheck.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel {
namespace {

using testkit::check_against_reference;
using testkit::PlanePair;
using testkit::PlaneTieKind;
using testkit::Query;
using testkit::ReferenceCheck;
using testkit::ulp_difference;
using testkit::ulp_distance;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// One step up in the order of ulp_distance: like nextafter(x, +inf), except that -0 → +0 is a step of its
// own (nextafter(-0, +inf) skips +0 and gives DBL_TRUE_MIN).
double next_up(double x) {
  if (x == 0 && std::signbit(x)) return 0.0;
  return std::nextafter(x, inf);
}

// ---------------------------------------------------------------------------------------------------------
// ulp_distance

TEST(UlpDistance, HandPickedValues) {
  EXPECT_EQ(ulp_distance(1.0, 1.0), 0u);
  EXPECT_EQ(ulp_distance(1.0, std::nextafter(1.0, 2.0)), 1u);
  EXPECT_EQ(ulp_distance(1.0, std::nextafter(1.0, 0.0)), 1u);  // across a binade boundary: still one step
  EXPECT_EQ(ulp_distance(-0.0, 0.0), 1u);
  EXPECT_EQ(ulp_distance(0.0, 0.0), 0u);
  EXPECT_EQ(ulp_distance(-0.0, -0.0), 0u);
  EXPECT_EQ(ulp_distance(0.0, DBL_TRUE_MIN), 1u);
  EXPECT_EQ(ulp_distance(-0.0, DBL_TRUE_MIN), 2u);
  EXPECT_EQ(ulp_distance(-DBL_TRUE_MIN, DBL_TRUE_MIN), 3u);
  EXPECT_EQ(ulp_distance(DBL_MAX, inf), 1u);
  EXPECT_EQ(ulp_distance(-inf, -DBL_MAX), 1u);
  EXPECT_EQ(ulp_distance(-inf, inf), 2 * 0x7ff0000000000000u + 1);
  EXPECT_EQ(ulp_distance(0.0, DBL_MIN), 0x0010000000000000u);  // 2^52 subnormals and +0 below DBL_MIN
  EXPECT_EQ(ulp_distance(1.0, 2.0), 0x0010000000000000u);      // one binade: 2^52 steps
  EXPECT_FALSE(ulp_distance(nan, 1.0).has_value());
  EXPECT_FALSE(ulp_distance(1.0, nan).has_value());
  EXPECT_FALSE(ulp_distance(nan, nan).has_value());
}

TEST(UlpDifference, SignFollowsTheOrder) {
  EXPECT_EQ(ulp_difference(1.0, std::nextafter(1.0, 2.0)), 1);
  EXPECT_EQ(ulp_difference(std::nextafter(1.0, 2.0), 1.0), -1);
  EXPECT_EQ(ulp_difference(0.0, -0.0), -1);
  EXPECT_EQ(ulp_difference(-1.0, 1.0), static_cast<std::int64_t>(2 * 0x3ff0000000000000u + 1));
  EXPECT_EQ(ulp_difference(-inf, inf), std::numeric_limits<std::int64_t>::max());  // saturated
  EXPECT_EQ(ulp_difference(inf, -inf), -std::numeric_limits<std::int64_t>::max());
  EXPECT_FALSE(ulp_difference(nan, 0.0).has_value());
}

// A double with random bits that is not NaN (pbrt-v4's float tests use the same kind of pattern).
double random_double(testkit::SplitMix64& rng) {
  for (;;) {
    const double x = std::bit_cast<double>(rng());
    if (!std::isnan(x)) return x;
  }
}

TEST(UlpDistance, CountsNextafterStepsOnRandomPatterns) {
  testkit::SplitMix64 rng(20240607);
  std::vector<double> starts{-DBL_TRUE_MIN * 3, -DBL_MIN, -1.0, -0.0, 0.0, DBL_MAX, -inf};
  for (int i = 0; i < 2000; ++i) starts.push_back(random_double(rng));
  for (const double start : starts) {
    double x = start;
    for (std::uint64_t k = 1; k <= 40 && x != inf; ++k) {
      x = next_up(x);
      ASSERT_EQ(ulp_distance(start, x), k) << std::hexfloat << start << " → " << x;
      ASSERT_EQ(ulp_distance(x, start), k);
      ASSERT_EQ(ulp_difference(start, x), static_cast<std::int64_t>(k));
    }
  }
}

TEST(UlpDistance, IsAdditiveAndZeroOnlyForTheSameBits) {
  testkit::SplitMix64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    double v[3] = {random_double(rng), random_double(rng), random_double(rng)};
    std::sort(v, v + 3, [](double a, double b) { return a < b || (a == b && std::signbit(a) && !std::signbit(b)); });
    const std::uint64_t ab = *ulp_distance(v[0], v[1]), bc = *ulp_distance(v[1], v[2]), ac = *ulp_distance(v[0], v[2]);
    ASSERT_EQ(ab + bc, ac) << std::hexfloat << v[0] << ' ' << v[1] << ' ' << v[2];
    ASSERT_EQ(ab == 0, test_support::same_bits(v[0], v[1]));
  }
}

TEST(UlpDistance, EqualsTheExactDifferenceOverTheQuantumWithinABinade) {
  // For a and b in one binade [2^e, 2^(e+1)) (or among the subnormals, quantum 2^-1074), the distance is
  // (b − a)/2^(e−52) exactly: checked in rationals.
  testkit::SplitMix64 rng(99);
  for (int i = 0; i < 5000; ++i) {
    const double a = std::fabs(random_double(rng));
    if (!std::isfinite(a) || a == 0) continue;
    int e = 0;
    std::frexp(a, &e);  // a = f·2^e, f in [0.5, 1): binade 2^(e−1)
    const int quantum_exponent = std::max(e - 1, -1022) - 52;
    const double top = a < DBL_MIN ? DBL_MIN : std::ldexp(1.0, e);  // the binade's end (excluded)
    const double b = std::nextafter(top, 0.0) - std::ldexp(static_cast<double>(rng() % 1000), quantum_exponent);
    if (b < a) continue;
    const mpq_class steps =
        (mpq_class(b) - mpq_class(a)) / (quantum_exponent >= 0 ? mpq_class(mpz_class(1) << quantum_exponent)
                                                               : mpq_class(1, mpz_class(1) << -quantum_exponent));
    ASSERT_EQ(steps.get_den(), 1);
    ASSERT_EQ(mpz_class(std::to_string(*ulp_distance(a, b))), steps.get_num()) << std::hexfloat << a << ' ' << b;
  }
}

// ---------------------------------------------------------------------------------------------------------
// check_against_reference

const Query one_tenth{{{0, 0, 0}, {10, 0, 0}}, {{1, 0, 0}, {1, 0, 0}}};  // hit, t = RN(1/10)

TEST(ReferenceCheck, TheExactAnswerPasses) {
  const ReferenceCheck c = check_against_reference(one_tenth, Intersection{Relation::hit, 0.1});
  EXPECT_TRUE(c.passed());
  EXPECT_TRUE(c.relation_matches);
  EXPECT_TRUE(c.t_compared);
  EXPECT_EQ(c.t_ulps, 0u);
  EXPECT_EQ(c.t_direction, 0);
  ASSERT_TRUE(c.exact_t.has_value());
  EXPECT_EQ(c.exact_t->str(), "1/10");
  EXPECT_EQ(c.exact_num.str(), "1/1");
  EXPECT_EQ(c.exact_den.str(), "10/1");
}

TEST(ReferenceCheck, CountsUlpsOfTAndHonoursTheTolerance) {
  const double above = std::nextafter(std::nextafter(0.1, 1.0), 1.0);
  const ReferenceCheck c = check_against_reference(one_tenth, Relation::hit, above);
  EXPECT_FALSE(c.passed());
  EXPECT_TRUE(c.relation_matches);
  EXPECT_EQ(c.t_ulps, 2u);
  EXPECT_EQ(c.t_direction, 1);
  EXPECT_FALSE(check_against_reference(one_tenth, Relation::hit, above, 1).passed());
  EXPECT_TRUE(check_against_reference(one_tenth, Relation::hit, above, 2).passed());
  const ReferenceCheck below = check_against_reference(one_tenth, Relation::hit, std::nextafter(0.1, 0.0));
  EXPECT_EQ(below.t_ulps, 1u);
  EXPECT_EQ(below.t_direction, -1);
}

TEST(ReferenceCheck, AWrongRelationFailsWhateverT) {
  const ReferenceCheck c = check_against_reference(one_tenth, Relation::behind, 0.1, 1000);
  EXPECT_FALSE(c.passed());
  EXPECT_FALSE(c.relation_matches);
  EXPECT_TRUE(c.t_matches());
  EXPECT_NE(c.report().find("FAILED: relation is behind, expected hit\n"), std::string::npos) << c.report();
}

TEST(ReferenceCheck, NanTFailsWhenATIsExpected) {
  const ReferenceCheck c = check_against_reference(one_tenth, Relation::hit, nan, 1u << 30);
  EXPECT_FALSE(c.passed());
  EXPECT_FALSE(c.t_ulps.has_value());
  EXPECT_NE(c.report().find("FAILED: t is nan, expected a number (tolerance 1073741824 ulps)"), std::string::npos)
      << c.report();
}

TEST(ReferenceCheck, ReportElidesTheMiddleOfHugeNumAndDenButNotT) {
  // Subnormal direction: den = -2^-1072 has a 323-digit denominator.
  const Query q{{{-1, -1, -1}, {-0x0.0000000000004p-1022, 0, 0}}, {{-1, -1, -1}, {-1, -1, -1}}};
  const ReferenceCheck c = check_against_reference(q, Relation::in_plane, nan);
  const std::string r = c.report();
  EXPECT_NE(r.find("t = num/den = 0/1, num = 0, den = 1/"), std::string::npos) << r;
  EXPECT_NE(r.find("...(323 digits)..."), std::string::npos) << r;
  EXPECT_EQ(c.exact_den.denominator.size(), 323u);
}

TEST(ReferenceCheck, TIsNotJudgedForParallelAndInPlane) {
  const Query parallel{{{0, 0, 0}, {1, 0, 0}}, {{0, 0, 5}, {0, 0, 1}}};
  const ReferenceCheck c = check_against_reference(parallel, Relation::parallel, 42.0);
  EXPECT_TRUE(c.passed());
  EXPECT_FALSE(c.t_compared);
  EXPECT_FALSE(c.exact_t.has_value());
  EXPECT_NE(c.report().find("42"), std::string::npos);  // what the code returned is still shown
  const Query in_plane{{{0, 0, 5}, {1, 0, 0}}, {{0, 0, 5}, {0, 0, 1}}};
  EXPECT_TRUE(check_against_reference(in_plane, Relation::in_plane, nan).passed());
  EXPECT_FALSE(check_against_reference(in_plane, Relation::parallel, nan).passed());
}

TEST(ReferenceCheck, SignedZeroIsOneUlpFromTheOther) {
  // Origin on the plane: t is exactly +0; -0 (what −(0)/den gives) is one ulp off.
  const Query on_plane{{{0, 0, 5}, {0, 0, -1}}, {{1, 1, 5}, {0, 0, 1}}};
  const ReferenceCheck c = check_against_reference(on_plane, Relation::hit, -0.0);
  EXPECT_EQ(c.t_ulps, 1u);
  EXPECT_FALSE(c.passed());
  EXPECT_TRUE(check_against_reference(on_plane, Relation::hit, -0.0, 1).passed());
}

TEST(ReferenceCheck, InvalidInputThrows) {
  const Query zero_direction{{{0, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {1, 0, 0}}};
  EXPECT_THROW((void)check_against_reference(zero_direction, Relation::hit, 0.0), invalid_input);
  const Query nan_origin{{{nan, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {1, 0, 0}}};
  EXPECT_THROW((void)check_against_reference(nan_origin, Relation::hit, 0.0), invalid_input);
}

TEST(ReferenceCheck, AgreesWithTheIndependentOracleOnEveryKind) {
  // The check's verdict on the oracle's answer is "passed, 0 ulps"; on the oracle's t moved by k ulps it is
  // "k ulps" in the right direction.
  testkit::SplitMix64 rng(11);
  const testkit::BitSource bits = [&rng] { return rng(); };
  for (const testkit::QueryKind kind : testkit::all_query_kinds) {
    for (int i = 0; i < 200; ++i) {
      const Query q = testkit::make_query(kind, bits);
      const Intersection truth = test_support::contract_answer(q.ray, q.plane);
      const ReferenceCheck c = check_against_reference(q, truth);
      ASSERT_TRUE(c.passed()) << c.report();
      if (!c.t_compared || std::isinf(truth.t)) continue;
      const int k = static_cast<int>(rng() % 5) + 1;
      double moved = truth.t;
      for (int j = 0; j < k; ++j) moved = std::nextafter(moved, inf);
      if (std::isinf(moved)) continue;
      const ReferenceCheck off = check_against_reference(q, Intersection{truth.relation, moved});
      // nextafter skips +0 from -0: one step fewer in its count than in ulp_distance.
      const std::uint64_t expected_steps = static_cast<std::uint64_t>(k) + (std::signbit(truth.t) && moved > 0 ? 1 : 0);
      ASSERT_EQ(off.t_ulps, expected_steps) << off.report();
      ASSERT_EQ(off.t_direction, 1);
    }
  }
}

// The replay line is 12 hexadecimal floats that strtod reads back to the query, bit for bit.
TEST(ReferenceCheck, ReportReplaysTheQueryExactly) {
  testkit::SplitMix64 rng(5);
  const testkit::BitSource bits = [&rng] { return rng(); };
  for (const testkit::QueryKind kind : testkit::all_query_kinds) {
    const Query q = testkit::make_query(kind, bits);
    std::istringstream in(testkit::classify_line(q));
    std::vector<double> read;
    for (std::string token; in >> token;) read.push_back(std::strtod(token.c_str(), nullptr));
    ASSERT_EQ(read.size(), 12u);
    const double given[12] = {q.ray.origin.x,    q.ray.origin.y,    q.ray.origin.z,   q.ray.direction.x,
                              q.ray.direction.y, q.ray.direction.z, q.plane.point.x,  q.plane.point.y,
                              q.plane.point.z,   q.plane.normal.x,  q.plane.normal.y, q.plane.normal.z};
    for (int i = 0; i < 12; ++i) ASSERT_TRUE(test_support::same_bits(read[static_cast<std::size_t>(i)], given[i])) << i;
  }
}

TEST(ReferenceCheck, ReportNamesEverything) {
  const std::string r = check_against_reference(one_tenth, Relation::behind, -0.5).report();
  for (const char* part :
       {"raykernel reference check FAILED: relation is behind, expected hit; t is ",
        "query     o = (0x0p+0, 0x0p+0, 0x0p+0)",
        "replay    echo '0x0p+0 0x0p+0 0x0p+0 0x1.4p+3 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0 0x1p+0 0x0p+0 0x0p+0' | "
        "raykernel classify --exact-t --hex",
        "expected  hit    t = 0x1.999999999999ap-4 (0.1)", "got       behind t = -0x1p-1 (-0.5)",
        "exact     t = num/den = 1/10, num = 1, den = 10", "ulps below the correctly rounded t (tolerance 0 ulps)"}) {
    EXPECT_NE(r.find(part), std::string::npos) << "missing: " << part << "\nin:\n" << r;
  }
  std::ostringstream os;
  os << check_against_reference(one_tenth, Relation::hit, 0.1);
  EXPECT_EQ(os.str().rfind("raykernel reference check passed", 0), 0u) << os.str();
}

// ---------------------------------------------------------------------------------------------------------
// Plane pairs with exact and near ties

struct PairTerms {
  mpq_class t[2];
};

void check_pair_promise(const PlanePair& pp, int i) {
  SCOPED_TRACE(std::string(testkit::to_string(pp.kind)) + " #" + std::to_string(i));
  PairTerms terms;
  for (int k = 0; k < 2; ++k) {
    ASSERT_FALSE(validate(pp.ray, pp.planes[static_cast<std::size_t>(k)]).has_value());
    const test_support::ExactTerms e = test_support::exact_terms(pp.ray, pp.planes[static_cast<std::size_t>(k)]);
    ASSERT_NE(e.den, 0);
    terms.t[k] = e.num / e.den;
    ASSERT_GT(terms.t[k], 0);  // both hit
  }
  const int exact_order = cmp(terms.t[1], terms.t[0]);
  ASSERT_EQ((exact_order > 0) - (exact_order < 0), pp.order);
  const bool exact_tie = pp.kind == PlaneTieKind::coincident || pp.kind == PlaneTieKind::pivot;
  if (exact_tie) {
    ASSERT_EQ(terms.t[0], terms.t[1]);
  } else {
    ASSERT_NE(terms.t[0], terms.t[1]);
    ASSERT_LT(abs(terms.t[1] - terms.t[0]), terms.t[0] / mpq_class(mpz_class(1) << 53));
    // Less than an ulp apart: the rounded values are equal or adjacent.
    const double r0 = test_support::round_by_integer_division(terms.t[0]), r1 = test_support::round_by_integer_division(terms.t[1]);
    ASSERT_LE(*ulp_distance(r0, r1), 1u);
  }
  // The geometry the kind promises.
  const Vec3 &n0 = pp.planes[0].normal, &n1 = pp.planes[1].normal;
  auto q = [](double x) { return mpq_class(x); };
  const mpq_class cx = q(n0.y) * q(n1.z) - q(n0.z) * q(n1.y), cy = q(n0.z) * q(n1.x) - q(n0.x) * q(n1.z),
                  cz = q(n0.x) * q(n1.y) - q(n0.y) * q(n1.x);
  const bool parallel_normals = cx == 0 && cy == 0 && cz == 0;
  const Vec3 &p0 = pp.planes[0].point, &p1 = pp.planes[1].point;
  const mpq_class offset =
      (q(p1.x) - q(p0.x)) * q(n0.x) + (q(p1.y) - q(p0.y)) * q(n0.y) + (q(p1.z) - q(p0.z)) * q(n0.z);
  switch (pp.kind) {
    case PlaneTieKind::coincident: EXPECT_TRUE(parallel_normals && offset == 0); break;
    case PlaneTieKind::parallel_offset: EXPECT_TRUE(parallel_normals && offset != 0); break;
    case PlaneTieKind::pivot:
    case PlaneTieKind::pivot_offset: EXPECT_FALSE(parallel_normals); break;
  }
  // The kernel agrees (docs/contract.md §4 compares exact t): the certified t round the same way as the oracle's.
  for (int k = 0; k < 2; ++k) {
    const Intersection x = intersect(pp.ray, pp.planes[static_cast<std::size_t>(k)]);
    EXPECT_EQ(x.relation, Relation::hit);
    EXPECT_TRUE(test_support::same_bits(x.t, test_support::round_by_integer_division(terms.t[k])));
  }
}

TEST(PlanePairs, EveryKindKeepsItsPromise) {
  testkit::SplitMix64 rng(314159);
  const testkit::BitSource bits = [&rng] { return rng(); };
  int nearest_is_second = 0, rounded_equal = 0, near_ties = 0;
  for (const PlaneTieKind kind : testkit::all_plane_tie_kinds) {
    for (int i = 0; i < 1000; ++i) {
      const PlanePair pp = testkit::make_plane_pair_near_tie(kind, bits);
      ASSERT_EQ(pp.kind, kind);
      check_pair_promise(pp, i);
      nearest_is_second += pp.nearest();
      if (pp.order != 0) {
        ++near_ties;
        rounded_equal +=
            intersect(pp.query(0).ray, pp.query(0).plane).t == intersect(pp.query(1).ray, pp.query(1).plane).t;
      }
    }
  }
  // Both winners occur, and most near ties round to the same double (what makes them hard).
  EXPECT_GT(nearest_is_second, 500);
  EXPECT_LT(nearest_is_second, 3500);
  EXPECT_GT(rounded_equal, near_ties / 2);
}

TEST(PlanePairs, MixedKindsAllZeroWordsAndDeterminism) {
  testkit::SplitMix64 rng(2718);
  const testkit::BitSource bits = [&rng] { return rng(); };
  for (int i = 0; i < 500; ++i) check_pair_promise(testkit::make_plane_pair_near_tie(bits), i);
  const testkit::BitSource zeros = [] { return std::uint64_t{0}; };  // what a shrinker tries first
  for (const PlaneTieKind kind : testkit::all_plane_tie_kinds)
    check_pair_promise(testkit::make_plane_pair_near_tie(kind, zeros), -1);
  testkit::SplitMix64 a(9), b(9);
  const PlanePair pa = testkit::make_plane_pair_near_tie([&a] { return a(); });
  const PlanePair pb = testkit::make_plane_pair_near_tie([&b] { return b(); });
  EXPECT_EQ(std::memcmp(&pa.planes, &pb.planes, sizeof pa.planes), 0);
  EXPECT_EQ(pa.order, pb.order);
}

// ---------------------------------------------------------------------------------------------------------
// The RapidCheck side (rapidcheck.hpp)

RC_GTEST_PROP(TestingGenerators, PlanePairsKeepTheirPromise, (const PlanePair& pp)) {
  RC_TAG(testkit::to_string(pp.kind));
  PairTerms terms;
  for (int k = 0; k < 2; ++k) {
    const test_support::ExactTerms e = test_support::exact_terms(pp.ray, pp.planes[static_cast<std::size_t>(k)]);
    RC_ASSERT(e.den != 0);
    terms.t[k] = e.num / e.den;
  }
  const int c = cmp(terms.t[1], terms.t[0]);
  RC_ASSERT((c > 0) - (c < 0) == pp.order);
}

RC_GTEST_PROP(TestingGenerators, HardQueriesOfChosenKinds, ()) {
  const testkit::KindedQuery k =
      *testkit::gen_hard_query({testkit::QueryKind::near_parallel, testkit::QueryKind::subnormal});
  RC_ASSERT(k.kind == testkit::QueryKind::near_parallel || k.kind == testkit::QueryKind::subnormal);
  RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(k.query, intersect(k.query.ray, k.query.plane), 0);
}

TEST(TestingGenerators, AFailingReferenceAssertionPrintsTheReport) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const bool ok = rc::check("naive against the reference", [](const testkit::KindedQuery& k) {
    RAYKERNEL_RC_ASSERT_MATCHES_REFERENCE(k.query, intersect_naive(k.query.ray, k.query.plane), 0);
  });
  const std::string out = ::testing::internal::GetCapturedStdout() + ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(ok);
  EXPECT_NE(out.find("Falsifiable"), std::string::npos) << out;
  EXPECT_NE(out.find("raykernel reference check FAILED"), std::string::npos) << out;
  EXPECT_NE(out.find("replay    echo '"), std::string::npos) << out;
}

}  // namespace
}  // namespace raykernel
