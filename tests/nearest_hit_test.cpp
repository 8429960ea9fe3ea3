// nearest_hit (docs/contract.md §4) and its certified comparison of two t values.
//
//  * Hand-derived cases: the loop of docs/ray-casting.md §1.1, ties, coincident planes, planes through one point of the ray,
//    two t closer than an ulp (where comparing rounded t picks the wrong plane), t = 0, planes never hit,
//    products that underflow (the exact stage), invalid input, a non-default floating-point environment.
//  * Each stage of the comparison on its own against exact rationals (like plane_stages_test.cpp): what a
//    stage certifies must be right, every enclosure must contain the exact Δ = num_a·den_b − num_b·den_a.
//  * RapidCheck: certified == brute-force exact nearest on generated scenes full of exact and near ties.
//  * The screen (stage 1 and the filter comparison over several planes at once): every screen and the
//    scalar loop on hand-derived sets of 0..9 planes (the decisive plane in every lane and in the tail) and
//    on generated scenes of up to 40 planes.
#include "support/oracle.hpp"
#include "support/plane_scenes.hpp"

#include "nearest/compare_quotients.hpp"
#include "core/enclosure.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "core/rational_from_double.hpp"
#include "nearest/nearest_hit_internal.hpp"
#include "nearest/nearest_screen.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/plane_pairs.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cfenv>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace raykernel {
namespace {

using detail::Sign;
using test_support::same_bits;

std::optional<NearestHit> hit(std::size_t plane, double t) { return NearestHit{plane, t}; }

// ---- Hand-derived cases ----------------------------------------------------------------------------------

// compare_hit_distances wires each stage-1 value to its own constant: num's enclosure with the num filter's
// constant, den's with den's (a mutation that gave num den's smaller constant left the differential runner and
// the other tests silent). Plane A: t = 1 from num = 1 (magnitude 1); plane B: t = 1 + 8ku from num = 2 + 8ku − 1,
// whose magnitude 3 gives num the widest enclosure; both den = 1. For k = 1..16 the comparison's stage-1
// margin |δ| = 8ku crosses its bound (about 26u with num's constant, 22u with den's), and the traced comparison
// must be decided by stage 1 exactly when compare_quotients_filter on the enclosures as specified is certain.
TEST(NearestHit, TheComparisonUsesEachValuesOwnConstant) {
  constexpr double u = 0x1p-53;
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const double d[3] = {1, 0, 0};
  int decided_by_filter = 0;
  for (int k = 1; k <= 16; ++k) {
    const Plane a{{1, 0, 0}, {1, 0, 0}};
    const Plane b{{2 + 8 * k * u, -1, 0}, {1, 1, 0}};  // 2 + 8ku: representable (ulp of 2 is 4u)
    const std::vector<Plane> planes{a, b};
    const TracedNearestHit traced = nearest_hit_traced(ray, planes);
    ASSERT_TRUE(traced.hit.has_value());
    EXPECT_EQ(traced.hit->plane, 0u) << k;
    auto enclosures = [&](const Plane& plane) {
      const double n[3] = {plane.normal.x, plane.normal.y, plane.normal.z};
      const double diff[3] = {plane.point.x, plane.point.y, plane.point.z};  // p − o with o = 0
      return std::pair{detail::filter_enclosure(detail::dot3_rounded(diff, n), detail::bounds::filter_num_relative),
                       detail::filter_enclosure(detail::dot3_rounded(d, n), detail::bounds::filter_den_relative)};
    };
    const auto [num_b, den_b] = enclosures(b);
    const auto [num_a, den_a] = enclosures(a);
    const bool certain = detail::is_certain(detail::compare_quotients_filter(num_b, den_b, num_a, den_a));
    decided_by_filter += certain;
    EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::filter)], certain ? 1u : 0u) << "k = " << k;
  }
  // The window is inside the loop: some k decided by stage 1, some not.
  EXPECT_GT(decided_by_filter, 0);
  EXPECT_LT(decided_by_filter, 16);
}

TEST(NearestHit, TheSeedsLoopPicksTheSmallestT) {
  // Ray along +z from the origin. Planes z = 5 (t = 5), z = 3 (t = 3), z = −2 (behind, t = −2),
  // x = 1 (parallel: d·n = 0, num = 1), y = 0 (in-plane: d·n = 0, num = 0).
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  const std::vector<Plane> planes = {{{0, 0, 5}, {0, 0, 1}},
                                     {{0, 0, 3}, {0, 0, -1}},
                                     {{0, 0, -2}, {0, 0, 1}},
                                     {{1, 0, 0}, {1, 0, 0}},
                                     {{0, 0, 0}, {0, 1, 0}}};
  EXPECT_EQ(nearest_hit(ray, planes), hit(1, 3.0));
  EXPECT_EQ(nearest_hit_exact(ray, planes), hit(1, 3.0));
  EXPECT_EQ(nearest_hit_naive(ray, planes), hit(1, 3.0));
}

TEST(NearestHit, PlanesThatAreNeverHitGiveAMiss) {
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  const std::vector<Plane> planes = {{{0, 0, -2}, {0, 0, 1}}, {{1, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {0, 1, 0}}};
  EXPECT_EQ(nearest_hit(ray, planes), std::nullopt);
  EXPECT_EQ(nearest_hit_exact(ray, planes), std::nullopt);
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{}), std::nullopt);
}

TEST(NearestHit, DuplicatedPlanesTieToTheSmallestIndex) {
  // Planes 1 and 2 are the same doubles, t = 4; plane 0 is farther (t = 6).
  const Ray ray{{0, 0, 0}, {0, 1, 0}};
  const Plane far{{0, 6, 0}, {0, 1, 0}}, near{{0, 4, 0}, {0, 1, 0}};
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{far, near, near}), hit(1, 4.0));
}

TEST(NearestHit, CoincidentPlanesWithAnotherRepresentationTie) {
  // The same plane z = 5 given twice: point (7, −3, 5) with normal (0, 0, 3), then point (0, 0, 5) with
  // normal (0, 0, 1). Along d = (1, 1, 10) from the origin: num = 15 and den = 30, resp. 5 and 10: both
  // t = 1/2 exactly, so the first (index 0) wins. The naive loop also computes 0.5 twice here.
  const Ray ray{{0, 0, 0}, {1, 1, 10}};
  const std::vector<Plane> planes = {{{7, -3, 5}, {0, 0, 3}}, {{0, 0, 5}, {0, 0, 1}}};
  EXPECT_EQ(nearest_hit(ray, planes), hit(0, 0.5));
  const std::vector<Plane> reversed = {planes[1], planes[0]};
  EXPECT_EQ(nearest_hit(ray, reversed), hit(0, 0.5));
}

TEST(NearestHit, PlanesThroughTheSamePointOfTheRayTie) {
  // Both planes pass through (1, 1, 1) = o + 1·d with o = 0, d = (1, 1, 1): t = 1 for any normal.
  // Plane 0: normal (1, 0, 0): num = 1, den = 1. Plane 1: normal (0.1, 0.7, −0.3) (doubles near those):
  // num = den exactly, whatever their rounding. Index 0 wins; reversed, index 0 (the other plane) wins.
  const Ray ray{{0, 0, 0}, {1, 1, 1}};
  const Plane a{{1, 1, 1}, {1, 0, 0}}, b{{1, 1, 1}, {0.1, 0.7, -0.3}};
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{a, b}), hit(0, 1.0));
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{b, a}), hit(0, 1.0));
}

TEST(NearestHit, OrdersTwoTCloserThanAnUlp) {
  // Ray o = 0, d = (1, 0, 0). Plane 0: x = 1, t = 1. Plane 1: point (1, 1, 0), normal (1, −2^-60, 0):
  // num = 1 − 2^-60, den = 1, so t = 1 − 2^-60 < 1; RN(t) = 1 (the ulp below 1 is 2^-53). Plane 1 is nearer,
  // although both t round to 1.0. With normal (1, +2^-60, 0), t = 1 + 2^-60 and plane 0 wins.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const Plane x1{{1, 0, 0}, {1, 0, 0}};
  const Plane nearer{{1, 1, 0}, {1, -0x1p-60, 0}}, farther{{1, 1, 0}, {1, 0x1p-60, 0}};
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{x1, nearer}), hit(1, 1.0));
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{nearer, x1}), hit(0, 1.0));
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{x1, farther}), hit(0, 1.0));
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{farther, x1}), hit(1, 1.0));
  // The naive loop computes num = RN(1 − 2^-60) = 1 and sees a tie: it keeps index 0, the wrong plane.
  EXPECT_EQ(nearest_hit_naive(ray, std::vector<Plane>{x1, nearer}), hit(0, 1.0));
}

TEST(NearestHit, OriginOnAPlaneIsTZeroAndComesFirst) {
  // The origin (0, 0, 2) lies on plane 1 (z = 2): t = +0, nearer than plane 0 at t = 3 (z = 5).
  const Ray ray{{0, 0, 2}, {0, 0, 1}};
  const std::vector<Plane> planes = {{{0, 0, 5}, {0, 0, 1}}, {{4, 4, 2}, {0, 0, -1}}};
  const std::optional<NearestHit> h = nearest_hit(ray, planes);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->plane, 1u);
  EXPECT_TRUE(same_bits(h->t, 0.0));
  // Two planes through the origin tie at t = 0: the smaller index.
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{planes[0], planes[1], {{0, 0, 2}, {1, 1, 1}}}), hit(1, 0.0));
}

TEST(NearestHit, TiesAtTZeroWithATinyPositiveT) {
  // Plane 1's exact t is 2^-1100 > 0, which rounds to +0; plane 0's t is exactly 0. Plane 0 is nearer,
  // though both report t = 0: the comparison uses the exact values, not the rounded ones.
  // Plane 1: point (2^-1074, 0, 0) normal (1, 0, 0), ray o = 0, d = (2^26, 0, 0): num = 2^-1074,
  // den = 2^26, t = 2^-1100.
  const Ray ray{{0, 0, 0}, {0x1p26, 0, 0}};
  const Plane at_origin{{0, 0, 0}, {1, 1, 0}}, tiny{{0x1p-1074, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{tiny, at_origin}), hit(1, 0.0));
  EXPECT_EQ(nearest_hit(ray, std::vector<Plane>{at_origin, tiny}), hit(0, 0.0));
}

TEST(NearestHit, UnderflowingProductsReachTheExactStage) {
  // The README's tiny query: d = (2^-600, 0, 0), planes with normal (2^-600, 0, 0): every product is about
  // 2^-1200, below the double range. Plane 0 at x = 2^-600 (t = 1), plane 1 at x = 2^-601 (t = 1/2),
  // plane 2 through the same point with normal (2^-600, 2^-600, 0): num = 2^-1201, den = 2^-1200, t = 1/2
  // again, a tie with plane 1 that only exact arithmetic can see. Plane 3 is plane 0 again with its normal
  // doubled: the prepared set sets it aside, so it costs no comparison.
  const Ray ray{{0, 0, 0}, {0x1p-600, 0, 0}};
  const std::vector<Plane> planes = {{{0x1p-600, 0, 0}, {0x1p-600, 0, 0}},
                                     {{0x1p-601, 0, 0}, {0x1p-600, 0, 0}},
                                     {{0x1p-601, 0, 0}, {0x1p-600, 0x1p-600, 0}},
                                     {{0x1p-600, 0, 0}, {0x1p-599, 0, 0}}};
  EXPECT_EQ(PlaneSet(planes).candidates().size(), 3u);
  const TracedNearestHit traced = nearest_hit_traced(ray, planes);
  EXPECT_EQ(traced.hit, hit(1, 0.5));
  EXPECT_EQ(traced.comparison_stage, Stage::exact);
  EXPECT_EQ(traced.relation_stage, Stage::exact);
  EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 2u);
  // Plain doubles see every plane as in-plane (0 = 0): a miss.
  EXPECT_EQ(nearest_hit_naive(ray, planes), std::nullopt);
}

TEST(NearestHit, StagesAreReportedForACleanCase) {
  // Three planes at t = 1, 2, 3 along +x: the filter decides every relation and comparison; t = 1 needs
  // the compensated rounding, the fast path for t.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const std::vector<Plane> planes = {{{3, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {1, 0, 0}}, {{2, 0, 0}, {1, 0, 0}}};
  const TracedNearestHit traced = nearest_hit_traced(ray, planes);
  EXPECT_EQ(traced.hit, hit(1, 1.0));
  EXPECT_EQ(traced.relation_stage, Stage::filter);
  EXPECT_EQ(traced.comparison_stage, Stage::filter);
  EXPECT_EQ(traced.t_stage, Stage::compensated);
  EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::filter)], 2u);
}

TEST(NearestHit, InvalidInputIsNamed) {
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const Plane good{{1, 0, 0}, {1, 0, 0}};
  auto reason = [](const Ray& r, const std::vector<Plane>& planes) -> std::string {
    try {
      (void)nearest_hit(r, planes);
    } catch (const invalid_input& e) {
      try {
        (void)nearest_hit_exact(r, planes);
      } catch (const invalid_input& e2) {
        EXPECT_STREQ(e.what(), e2.what());
      }
      return e.what();
    }
    return "no exception";
  };
  EXPECT_EQ(reason(ray, {good, good, {{0, 0, 0}, {0, -0.0, 0}}}), "plane 2: plane normal is the zero vector");
  EXPECT_EQ(reason(ray, {{{0, std::numeric_limits<double>::quiet_NaN(), 0}, {1, 0, 0}}}), "plane 0: plane point y is NaN");
  EXPECT_EQ(reason({{0, 0, 0}, {0, 0, 0}}, {good}), "ray direction is the zero vector");
  EXPECT_EQ(reason({{HUGE_VAL, 0, 0}, {1, 0, 0}}, {good}), "ray origin x is +inf");
  // A zero direction is invalid even with no planes.
  EXPECT_EQ(reason({{0, 0, 0}, {0, 0, 0}}, {}), "ray direction is the zero vector");
  EXPECT_EQ(validate(Plane{{0, 0, 0}, {0, 0, 0}}), std::optional<std::string>("plane normal is the zero vector"));
  EXPECT_EQ(validate(Ray{{0, 0, 0}, {0, 0, 1}}), std::nullopt);
  // The prepared set names the plane the same way.
  EXPECT_THROW((void)PlaneSet(std::vector<Plane>{good, {{0, 0, 0}, {0, 0, 0}}}), invalid_input);
}

TEST(NearestHit, DirectedRoundingGivesTheDefaultEnvironmentsAnswer) {
  // Under FE_UPWARD the certified error bounds do not hold; nearest_hit installs round-to-nearest for the
  // call, answers as it would by default (the same stages), and restores FE_UPWARD. Plane 1: (p − o)·n =
  // 1 − 2^-60 and d·n = 1, so t = 1 − 2^-60, nearer than plane 0's t = 1 and rounding to 1 (2^-60 is less
  // than half the gap 2^-53 below 1); plane 2: t = 3.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  const std::vector<Plane> planes = {{{1, 0, 0}, {1, 0, 0}}, {{1, 1, 0}, {1, -0x1p-60, 0}}, {{3, 0, 0}, {1, 0, 3}}};
  const TracedNearestHit by_default = nearest_hit_traced(ray, planes);
  ASSERT_EQ(std::fesetround(FE_UPWARD), 0);
  const TracedNearestHit traced = nearest_hit_traced(ray, planes);
  const int mode_after = std::fegetround();
  std::fesetround(FE_TONEAREST);
  EXPECT_EQ(mode_after, FE_UPWARD);
  EXPECT_EQ(traced.hit, hit(1, 1.0));
  EXPECT_EQ(traced.hit, by_default.hit);
  EXPECT_EQ(traced.comparison_stage, by_default.comparison_stage);
}

TEST(RationalFromDouble, IsTheExactValue) {
  for (double x : {0.0, -0.0, 1.0, -0.1, 0x1p-1074, -0x1.fffffffffffffp-1023, 0x1p-1022, 1e308, -0x1.8p+1023, 3.0})
    EXPECT_EQ(detail::exact::rational_from_double(x), mpq_class(x)) << std::hexfloat << x;
}

// ---- Each comparison stage against exact rationals -------------------------------------------------------

// The exact Δ = num_a·den_b − num_b·den_a.
mpq_class exact_delta(const Ray& ray, const Plane& a, const Plane& b) {
  const test_support::ExactTerms ta = test_support::exact_terms(ray, a), tb = test_support::exact_terms(ray, b);
  return ta.num * tb.den - tb.num * ta.den;
}

bool encloses(const detail::Enclosure& e, const mpq_class& exact) {
  if (!(e.radius < HUGE_VAL)) return true;  // +inf or NaN: no information, always true
  if (!std::isfinite(e.hi) || !std::isfinite(e.lo)) return false;
  return abs(exact - (mpq_class(e.hi) + mpq_class(e.lo))) <= mpq_class(e.radius);
}

struct StageTally {
  int pairs = 0, filter = 0, compensated = 0, expansion = 0, ties = 0, filter_sign_of_delta_wrong = 0;
};

// Runs every stage on the pair (a, b) along `ray` and checks whatever they certify.
void check_pair(const Ray& ray, const Plane& a, const Plane& b, StageTally& tally, const std::string& context) {
  SCOPED_TRACE(context);
  const mpq_class delta = exact_delta(ray, a, b);
  const int sign = sgn(delta);
  detail::RayPlaneCascade qa(ray, a), qb(ray, b);
  ++tally.pairs;
  if (sign == 0) ++tally.ties;

  // Stage 1, from the stage-1 values and bounds.
  const detail::RoundedEnclosure na = detail::filter_enclosure(qa.terms().num, detail::bounds::filter_num_relative);
  const detail::RoundedEnclosure da = detail::filter_enclosure(qa.terms().den, detail::bounds::filter_den_relative);
  const detail::RoundedEnclosure nb = detail::filter_enclosure(qb.terms().num, detail::bounds::filter_num_relative);
  const detail::RoundedEnclosure db = detail::filter_enclosure(qb.terms().den, detail::bounds::filter_den_relative);
  const Sign s1 = detail::compare_quotients_filter(na, da, nb, db);
  if (s1 != Sign::uncertain) {
    ++tally.filter;
    ASSERT_EQ(static_cast<int>(s1), sign) << "the filter certified a wrong sign of Δ";
  } else {
    // The bound mattered: the unguarded rounded δ = P ⊖ Q would have the wrong sign here.
    const double p = na.value * db.value, q = nb.value * da.value;
    const double d = p - q;
    if ((d > 0 ? 1 : (d < 0 ? -1 : 0)) != sign) ++tally.filter_sign_of_delta_wrong;
  }

  // Stage 2: the enclosure contains Δ, and its sign is right when certain.
  const detail::Enclosure e2 = detail::compare_quotients_compensated(qa.num_compensated(), qa.den_compensated(),
                                                                     qb.num_compensated(), qb.den_compensated());
  ASSERT_TRUE(encloses(e2, delta)) << "compensated enclosure of Δ: " << std::hexfloat << e2.hi << " + " << e2.lo
                                   << " ± " << e2.radius;
  const Sign s2 = detail::enclosure_sign(e2);
  if (s2 != Sign::uncertain) {
    ++tally.compensated;
    ASSERT_EQ(static_cast<int>(s2), sign) << "the compensated stage certified a wrong sign of Δ";
  }

  // Stage 3: exact whenever both inputs are exact expansions and no product underflows.
  const Sign s3 = detail::compare_quotients_expansion(qa.expansions(), qb.expansions());
  if (s3 != Sign::uncertain) {
    ++tally.expansion;
    ASSERT_EQ(static_cast<int>(s3), sign) << "the expansion stage certified a wrong sign of Δ";
  }
}

class CompareStagesOnHardQueries : public ::testing::TestWithParam<testkit::QueryKind> {};

TEST_P(CompareStagesOnHardQueries, EachStageIsRightWhenItDecides) {
  // Pairs of planes along one ray: the first from a hard query of this kind, the second from another
  // hard query of the same kind (a different plane), a copy of the first moved by an ulp, a coincident
  // copy (normal scaled by −3 when exact), or the first plane again.
  const testkit::QueryKind kind = GetParam();
  const std::uint64_t seed = 0xc0de0000 + static_cast<std::uint64_t>(kind);
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE(std::string(testkit::to_string(kind)) + ", seed " + std::to_string(seed));
  StageTally tally;
  for (int i = 0; i < 1500 && !::testing::Test::HasFatalFailure(); ++i) {
    const testkit::Query q = testkit::make_query(kind, bits);
    Plane other = testkit::make_query(kind, bits).plane;
    switch (i % 4) {
      case 0: break;
      case 1: other = q.plane; other.point.x = std::nextafter(other.point.x, HUGE_VAL); break;
      case 2: {
        const Vec3 n{-3 * q.plane.normal.x, -3 * q.plane.normal.y, -3 * q.plane.normal.z};
        const bool exact = mpq_class(n.x) == -3 * mpq_class(q.plane.normal.x) &&
                           mpq_class(n.y) == -3 * mpq_class(q.plane.normal.y) &&
                           mpq_class(n.z) == -3 * mpq_class(q.plane.normal.z);
        other = exact ? Plane{q.plane.point, n} : q.plane;
        break;
      }
      case 3: other = q.plane; break;
    }
    check_pair(q.ray, q.plane, other, tally, "pair " + std::to_string(i));
  }
  EXPECT_EQ(tally.pairs, 1500);
  EXPECT_GE(tally.ties, 375);  // every fourth pair is the same plane twice
  RecordProperty("filter_decisions", tally.filter);
  RecordProperty("expansion_decisions", tally.expansion);
}

INSTANTIATE_TEST_SUITE_P(AllKinds, CompareStagesOnHardQueries, ::testing::ValuesIn(testkit::all_query_kinds),
                         [](const auto& info) {
                           std::string name(testkit::to_string(info.param));
                           for (char& c : name) c = (c == '-') ? '_' : c;
                           return name;
                         });

TEST(CompareStages, EachStageIsRightOnGeneratedScenes) {
  // Every pair of planes of 3000 generated scenes (pivots, near pivots, duplicates, coincident twins,
  // offsets by one ulp, hard-query planes). Also shows that each stage is exercised, and that the filter's
  // bound is needed: on many pairs the unguarded sign of δ is wrong.
  const std::uint64_t seed = 0x5ce9e5;
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  SCOPED_TRACE("seed " + std::to_string(seed));
  StageTally tally;
  for (int i = 0; i < 3000 && !::testing::Test::HasFatalFailure(); ++i) {
    const test_support::PlaneScene scene = test_support::make_plane_scene(bits);
    for (std::size_t a = 0; a < scene.planes.size(); ++a)
      for (std::size_t b = a + 1; b < scene.planes.size(); ++b)
        check_pair(scene.ray, scene.planes[a], scene.planes[b], tally,
                   "scene " + std::to_string(i) + ", planes " + std::to_string(a) + " and " + std::to_string(b) + "\n" +
                       test_support::describe_scene(scene));
  }
  EXPECT_GT(tally.filter, tally.pairs / 4);
  EXPECT_GT(tally.compensated, 100);
  EXPECT_GT(tally.expansion, 100);
  EXPECT_GT(tally.ties, 100);
  EXPECT_GT(tally.filter_sign_of_delta_wrong, 10);
  RecordProperty("pairs", tally.pairs);
}

TEST(CompareStages, FilterOnHandPickedValues) {
  using detail::RoundedEnclosure;
  // t_1 = 1/3 vs t_2 = 1/2 with exact inputs (radius 0): Δ = 1·2 − 1·3 = −1 < 0.
  EXPECT_EQ(detail::compare_quotients_filter({1, 0}, {3, 0}, {1, 0}, {2, 0}), Sign::negative);
  // Exact equality 2/4 vs 1/2 cannot be certified by a filter (its bound is positive).
  EXPECT_EQ(detail::compare_quotients_filter({2, 0}, {4, 0}, {1, 0}, {2, 0}), Sign::uncertain);
  // Radii wide enough to swallow the difference: 1/3 ± 1/2 vs 1/2.
  EXPECT_EQ(detail::compare_quotients_filter({1, 0.5}, {3, 0}, {1, 0}, {2, 0}), Sign::uncertain);
  // Overflow: P = 2^1000·2^1000 is +inf, the bound is +inf: uncertain, never a sign.
  EXPECT_EQ(detail::compare_quotients_filter({0x1p1000, 0}, {1, 0}, {1, 0}, {0x1p1000, 0}), Sign::uncertain);
  // A NaN radius (an overflowed stage-1 bound) gives no decision either.
  EXPECT_EQ(detail::compare_quotients_filter({1, std::numeric_limits<double>::quiet_NaN()}, {3, 0}, {1, 0}, {2, 0}),
            Sign::uncertain);
}

TEST(CompareStages, CompensatedSeparatesWhatTheFilterCannot) {
  // N_1/D_1 = (1 + 2^-60)/1 vs N_2/D_2 = 1/1, N_1 given as the double-double 1 + 2^-60 (exact, radius
  // 2^-1074): Δ = 2^-60 > 0. The one-double value of N_1 is 1, so stage 1 sees a tie.
  const detail::Enclosure n1{1, 0x1p-60, 0x1p-1074}, d1{1, 0, 0x1p-1074}, n2{1, 0, 0x1p-1074}, d2{1, 0, 0x1p-1074};
  EXPECT_EQ(detail::compare_quotients_filter({1, 0x1p-52}, {1, 0x1p-1074}, {1, 0x1p-1074}, {1, 0x1p-1074}), Sign::uncertain);
  const detail::Enclosure delta = detail::compare_quotients_compensated(n1, d1, n2, d2);
  EXPECT_TRUE(encloses(delta, mpq_class(mpz_class(1), mpz_class(1) << 60)));
  EXPECT_EQ(detail::enclosure_sign(delta), Sign::positive);
  // Overflowing inputs: radius +inf, no decision.
  const detail::Enclosure huge{0x1p1000, 0, 0};
  EXPECT_EQ(detail::enclosure_sign(detail::compare_quotients_compensated(huge, d1, n2, huge)), Sign::uncertain);
}

TEST(CompareStages, CompensatedBoundCoversTheDroppedProductOfLowParts) {
  // N_1 = 1 + 2^-53 (as 1 + lo, which TwoSum keeps: 1 + 2^-53 is a tie that rounds to 1), D_2 the same,
  // N_2 = 1 + 2^-52, D_1 = 1, all exact (radius 0). Δ = (1 + u)² − (1 + 2u) = u² = 2^-106. The stage
  // drops α_1·β_2 = u²: hi = S = −2^-52, lo = c_1 = 2^-52, so hi + lo = 0 and only the radius
  // (≥ 2^-101·|P| + |Q|) covers Δ.
  const detail::Enclosure n1{1, 0x1p-53, 0}, d1{1, 0, 0}, n2{1 + 0x1p-52, 0, 0}, d2{1, 0x1p-53, 0};
  const detail::Enclosure e = detail::compare_quotients_compensated(n1, d1, n2, d2);
  EXPECT_EQ(e.hi, -0x1p-52);
  EXPECT_EQ(e.lo, 0x1p-52);
  EXPECT_GE(e.radius, 0x1p-106);
  EXPECT_TRUE(encloses(e, mpq_class(mpz_class(1), mpz_class(1) << 106)));
  EXPECT_EQ(detail::enclosure_sign(e), Sign::uncertain);  // Δ > 0 but far below the radius: stage 3 decides
}

// The two enclosure stages are functions of enclosures, so they must be right for every value the
// enclosures allow, not only for the values a ray–plane query produces (whose errors are typically far
// below the bounds). Δ is bilinear, so its extremes over the box of allowed values are at the 16 corners
// (N_i = x_i ± e_i, D_i = y_i ± f_i): each corner is checked in exact rationals. Near ties with radii of
// the order of the difference put corners on both sides of zero, so a bound that is too small fails here.
TEST(CompareStages, EnclosureStagesHoldAtEveryCornerOfTheirInputs) {
  const std::uint64_t seed = 0xb0c5;
  testkit::SplitMix64 rng(seed);
  SCOPED_TRACE("seed " + std::to_string(seed));
  auto uniform = [&rng](int lo, int hi) { return lo + static_cast<int>(rng() % static_cast<std::uint64_t>(hi - lo + 1)); };
  auto significand = [&rng] { return 1 + static_cast<double>(rng() >> 12) * 0x1p-52; };
  int filter_decided = 0, compensated_decided = 0, corners_on_both_sides = 0;
  for (int i = 0; i < 20000 && !HasFailure(); ++i) {
    // Near-tie values: x_2/y_2 within a few ulps of x_1/y_1, signs and scales random.
    const int scale = uniform(-30, 30);
    const double y1 = std::ldexp(significand(), scale + uniform(-3, 3)) * (rng() & 1 ? 1 : -1);
    const double x1 = std::ldexp(significand(), scale + uniform(-3, 3)) * (rng() & 1 ? 1 : -1);
    const double y2 = std::ldexp(significand(), scale + uniform(-3, 3)) * (rng() & 1 ? 1 : -1);
    double x2 = x1 / y1 * y2;
    for (int k = uniform(-6, 6); k != 0; k += (k > 0 ? -1 : 1)) x2 = std::nextafter(x2, k > 0 ? HUGE_VAL : -HUGE_VAL);
    // Radii: zero, or a random fraction 2^-r of the value, r spread so that some radii matter and some not.
    auto radius = [&](double v) { return rng() % 4 == 0 ? 0.0 : std::ldexp(std::fabs(v), -uniform(44, 64)); };
    const double e1 = radius(x1), f1 = radius(y1), e2 = radius(x2), f2 = radius(y2);
    // Low parts for the double-double inputs: up to an ulp, so that hi + lo is a finer value.
    auto low = [&](double v) { return rng() % 2 ? 0.0 : std::ldexp(std::fabs(v), -uniform(54, 70)) * (rng() & 1 ? 1 : -1); };
    const detail::Enclosure n1{x1, low(x1), e1}, d1{y1, low(y1), f1}, n2{x2, low(x2), e2}, d2{y2, low(y2), f2};

    const Sign s1 = detail::compare_quotients_filter({x1, e1}, {y1, f1}, {x2, e2}, {y2, f2});
    const detail::Enclosure delta = detail::compare_quotients_compensated(n1, d1, n2, d2);
    const Sign s2 = detail::enclosure_sign(delta);
    filter_decided += s1 != Sign::uncertain;
    compensated_decided += s2 != Sign::uncertain;
    int signs_seen = 0;
    for (int corner = 0; corner < 16; ++corner) {
      auto pick = [corner](const mpq_class& v, double r, int bit) -> mpq_class {
        if ((corner >> bit) & 1) return v + mpq_class(r);
        return v - mpq_class(r);
      };
      // Stage 1's inputs are single doubles.
      const mpq_class N1 = pick(mpq_class(x1), e1, 0), D1 = pick(mpq_class(y1), f1, 1);
      const mpq_class N2 = pick(mpq_class(x2), e2, 2), D2 = pick(mpq_class(y2), f2, 3);
      const int exact1 = sgn(mpq_class(N1 * D2 - N2 * D1));
      signs_seen |= exact1 > 0 ? 1 : (exact1 < 0 ? 2 : 4);
      if (s1 != Sign::uncertain) {
        ASSERT_EQ(static_cast<int>(s1), exact1) << "filter, instance " << i << ", corner " << corner;
      }
      // Stage 2's inputs are double-doubles.
      const mpq_class M1 = pick(mpq_class(n1.hi) + mpq_class(n1.lo), e1, 0), E1 = pick(mpq_class(d1.hi) + mpq_class(d1.lo), f1, 1);
      const mpq_class M2 = pick(mpq_class(n2.hi) + mpq_class(n2.lo), e2, 2), E2 = pick(mpq_class(d2.hi) + mpq_class(d2.lo), f2, 3);
      const mpq_class exact2 = M1 * E2 - M2 * E1;
      ASSERT_TRUE(encloses(delta, exact2)) << "compensated enclosure, instance " << i << ", corner " << corner;
      if (s2 != Sign::uncertain) {
        ASSERT_EQ(static_cast<int>(s2), sgn(exact2)) << "compensated sign, instance " << i;
      }
    }
    corners_on_both_sides += signs_seen == 3 || signs_seen == 7;
  }
  EXPECT_GT(filter_decided, 1000);
  EXPECT_GT(compensated_decided, 2000);
  EXPECT_GT(corners_on_both_sides, 1000);
}

// ---- Properties: certified nearest == brute-force exact nearest ------------------------------------------

rc::Gen<test_support::PlaneScene> gen_plane_scene() {
  return rc::gen::exec([] {
    const testkit::BitSource bits = [] {
      return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max());
    };
    return test_support::make_plane_scene(bits);
  });
}

RC_GTEST_PROP(NearestHitProperty, CertifiedEqualsBruteForceExact, ()) {
  const test_support::PlaneScene scene = *gen_plane_scene();
  const test_support::OracleNearest expected = test_support::brute_force_nearest(scene.ray, scene.planes);
  const TracedNearestHit got = nearest_hit_traced(scene.ray, scene.planes);
  RC_CLASSIFY(!expected.plane, "miss");
  RC_CLASSIFY(got.comparison_stage != Stage::filter, std::string("comparison needed ") + std::string(to_string(got.comparison_stage)));
  if (!expected.plane) {
    RC_ASSERT(!got.hit.has_value());
    return;
  }
  RC_ASSERT(got.hit.has_value());
  RC_ASSERT(got.hit->plane == *expected.plane);
  RC_ASSERT(same_bits(got.hit->t, expected.rounded_t()));
  std::uint32_t comparisons = 0;
  for (std::uint32_t c : got.comparisons) comparisons += c;
  RC_ASSERT(comparisons < scene.planes.size());  // at most one per hit plane after the first
}

RC_GTEST_PROP(NearestHitProperty, ExactPathEqualsBruteForceExact, ()) {
  const test_support::PlaneScene scene = *gen_plane_scene();
  const test_support::OracleNearest expected = test_support::brute_force_nearest(scene.ray, scene.planes);
  const std::optional<NearestHit> got = nearest_hit_exact(scene.ray, scene.planes);
  RC_ASSERT(got.has_value() == expected.plane.has_value());
  if (got) {
    RC_ASSERT(got->plane == *expected.plane);
    RC_ASSERT(same_bits(got->t, expected.rounded_t()));
  }
}

RC_GTEST_PROP(NearestHitProperty, ReversingThePlaneOrderKeepsTheNearestPlane, ()) {
  // The nearest plane is the same geometric choice in either order; only ties move (to the other end).
  const test_support::PlaneScene scene = *gen_plane_scene();
  std::vector<Plane> reversed(scene.planes.rbegin(), scene.planes.rend());
  const std::optional<NearestHit> forward = nearest_hit(scene.ray, scene.planes);
  const std::optional<NearestHit> backward = nearest_hit(scene.ray, reversed);
  RC_ASSERT(forward.has_value() == backward.has_value());
  if (!forward) return;
  RC_ASSERT(same_bits(forward->t, backward->t));
  const std::size_t mirrored = scene.planes.size() - 1 - backward->plane;
  // Same exact t: either the same plane, or a tie.
  const test_support::ExactTerms a = test_support::exact_terms(scene.ray, scene.planes[forward->plane]);
  const test_support::ExactTerms b = test_support::exact_terms(scene.ray, scene.planes[mirrored]);
  RC_ASSERT(a.num * b.den == b.num * a.den);
  RC_ASSERT(mirrored >= forward->plane);  // the forward winner is the first of the tied planes
}

RC_GTEST_PROP(NearestHitProperty, OrdersTheTestingLibrarysNearTiePairs, ()) {
  // raykernel::testkit's plane pairs (exact ties, and t less than an ulp apart, with the order known by
  // construction), in both orders: the answer is the pair's own nearest(), and the two t round alike.
  const testkit::PlanePair pp = *rc::gen::exec([] {
    return testkit::make_plane_pair_near_tie(
        [] { return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max()); });
  });
  RC_TAG(std::string(testkit::to_string(pp.kind)));
  const std::vector<Plane> forward = {pp.planes[0], pp.planes[1]}, backward = {pp.planes[1], pp.planes[0]};
  const std::optional<NearestHit> a = nearest_hit(pp.ray, forward), b = nearest_hit(pp.ray, backward);
  RC_ASSERT(a.has_value() && b.has_value());
  RC_ASSERT(a->plane == static_cast<std::size_t>(pp.nearest()));
  // Reversed: plane 1 is index 0; on a tie the new index 0 wins.
  RC_ASSERT(b->plane == (pp.order == 0 ? 0u : static_cast<std::size_t>(1 - pp.nearest())));
  RC_ASSERT(same_bits(a->t, intersect_exact(pp.ray, pp.planes[static_cast<std::size_t>(pp.nearest())]).t));
}

RC_GTEST_PROP(NearestHitProperty, AgreesWithIntersectOnTheWinner, ()) {
  // The winner's t is intersect()'s t for that plane, and no plane hit by intersect() is nearer.
  const test_support::PlaneScene scene = *gen_plane_scene();
  const std::optional<NearestHit> h = nearest_hit(scene.ray, scene.planes);
  for (std::size_t k = 0; k < scene.planes.size(); ++k) {
    const Intersection i = intersect(scene.ray, scene.planes[k]);
    if (i.relation == Relation::hit) {
      RC_ASSERT(h.has_value());
      RC_ASSERT(h->t <= i.t);
    }
  }
  if (h) {
    const Intersection i = intersect(scene.ray, scene.planes[h->plane]);
    RC_ASSERT(i.relation == Relation::hit);
    RC_ASSERT(same_bits(i.t, h->t));
  }
}

// ---- The screen (nearest/nearest_screen.hpp): every screen and the scalar loop on the same sets ---------
//
// nearest_traced_with_screen runs a given screen whatever the set's size (the public entry points use it
// from 8 candidate planes on): the scalar loop (null), the portable screen (two planes at a time) and the
// screen this CPU gets (AVX2: four at a time). Sizes 0..9 put the decisive planes in every lane and in the
// tail of a group. Expected answers are derived by hand in the comments, and nearest_hit_exact agrees.

struct NamedScreen {
  const char* name;
  nearest_kernel::ScreenFunction screen;
};
const nearest_kernel::ScreenFunctions portable_screen{nearest_kernel::portable::reference, nearest_kernel::portable::screen};
std::vector<NamedScreen> every_screen() {
  return {{"scalar loop", nullptr}, {"portable screen", &portable_screen}, {"chosen screen", detail::chosen_screen()}};
}

// Each screen, and the public entry points, give `expected`; so does the exact path.
void expect_every_path(const Ray& ray, const std::vector<Plane>& planes, const std::optional<NearestHit>& expected,
                       const std::string& context) {
  const PlaneSet set(planes);
  for (const NamedScreen& s : every_screen()) {
    const TracedNearestHit got = detail::nearest_traced_with_screen(ray, set, s.screen);
    EXPECT_EQ(got.hit, expected) << s.name << ", " << context;
  }
  EXPECT_EQ(nearest_hit(ray, set), expected) << context;
  EXPECT_EQ(nearest_hit_traced(ray, set).hit, expected) << context;
  EXPECT_EQ(nearest_hit_exact(ray, planes), expected) << context;
}

TEST(NearestScreen, TheNearestPlaneInEveryPositionOfZeroToNinePlanes) {
  // Ray o = 0, d = (1, 0, 0). Plane k ≠ j: x = 10 + k (t = 10 + k; normal ±x alternating: num and den both
  // change sign, t does not), except every third plane, x = −(10 + k) (behind). Plane j: x = 1, t = 1.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  for (int n = 0; n <= 9; ++n) {
    auto make = [&](int j) {
      std::vector<Plane> planes;
      for (int k = 0; k < n; ++k) {
        const double normal_x = k % 2 == 0 ? 1.0 : -1.0;
        const double x = k == j ? 1.0 : (k % 3 == 2 ? -(10.0 + k) : 10.0 + k);
        planes.push_back({{x, 0, 0}, {normal_x, 0, 0}});
      }
      return planes;
    };
    // No nearest plane: the nearest of the others is k = 0 (t = 10) when there is one.
    expect_every_path(ray, make(-1), n == 0 ? std::nullopt : hit(0, 10.0), "n = " + std::to_string(n) + ", j = none");
    for (int j = 0; j < n; ++j)
      expect_every_path(ray, make(j), hit(static_cast<std::size_t>(j), 1.0),
                        "n = " + std::to_string(n) + ", j = " + std::to_string(j));
  }
}

TEST(NearestScreen, TiesAcrossLaneBoundariesGoToTheSmallestIndex) {
  // Ray o = 0, d = (1, 0, 0). Planes k < s: through (7, 0, 0), normal (1, k, 0): num = 7, den = 1, t = 7.
  // Planes k ≥ s: through (5, 0, 0), normal (1, k, 0): t = 5 exactly, all distinct planes (no two normals
  // parallel), so none is set aside and all tie: plane s wins, wherever s and the tied planes fall among
  // the lanes. Then the same with t = 5 planes only at s and at the last index (the others at t = 7).
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  for (int n = 1; n <= 9; ++n)
    for (int s = 0; s < n; ++s) {
      std::vector<Plane> planes, sparse;
      for (int k = 0; k < n; ++k) {
        const Vec3 normal{1, static_cast<double>(k), 0};
        planes.push_back({{k < s ? 7.0 : 5.0, 0, 0}, normal});
        sparse.push_back({{k == s || k == n - 1 ? 5.0 : 7.0, 0, 0}, normal});
      }
      const std::string context = "n = " + std::to_string(n) + ", s = " + std::to_string(s);
      expect_every_path(ray, planes, hit(static_cast<std::size_t>(s), 5.0), context);
      expect_every_path(ray, sparse, hit(static_cast<std::size_t>(s), 5.0), context + " (sparse)");
    }
}

TEST(NearestScreen, PlanesSetAsideKeepTheirIndices) {
  // Ray o = 0, d = (1, 0, 0). Indices: 0 x = 3 (t = 3), 1 the same plane with normal (2, 0, 0), 2 x = 4,
  // 3 the same plane with normal (−1, 0, 0), 4 x = 6, 5 x = 8, 6 x = 9, 7 the plane x + y = 2.5 (t = 2.5),
  // 8 the same plane through (3.5, −1, 0), 9 x = 1.5 (t = 1.5). Planes 1, 3 and 8 are set aside: 7
  // candidates, the winner is index 9 (the candidates' 7th), t = 1.5.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  std::vector<Plane> planes = {{{3, 0, 0}, {1, 0, 0}},   {{3, 5, 0}, {2, 0, 0}},     {{4, 0, 0}, {1, 0, 0}},
                               {{4, 1, 1}, {-1, 0, 0}},  {{6, 0, 0}, {1, 0, 0}},     {{8, 0, 0}, {1, 0, 0}},
                               {{9, 0, 0}, {1, 0, 0}},   {{2.5, 0, 0}, {1, 1, 0}},   {{3.5, -1, 0}, {1, 1, 0}},
                               {{1.5, 0, 0}, {1, 0, 0}}};
  EXPECT_EQ(PlaneSet(planes).candidates().size(), 7u);
  expect_every_path(ray, planes, hit(9, 1.5), "winner after three set-aside planes");
  // The nearest plane given twice, at 2 and again at 9 (its coincident twin, normal (3, 0, 0)): index 2.
  planes[2] = {{1.5, 0, 0}, {1, 0, 0}};
  planes[9] = {{1.5, 7, 7}, {3, 0, 0}};
  expect_every_path(ray, planes, hit(2, 1.5), "winner with a twin set aside");
}

TEST(NearestScreen, PlanesStageOneCannotDecideAreExamined) {
  // Ray o = 0, d = (2^-600, 0, 0). Certain planes: x = (k + 2)·2^-600, normal (1, 0, 0): num = (k + 2)·2^-600,
  // den = 2^-600, t = k + 2 ≥ 2. Uncertain planes (normal (2^-600, 0, 0): every product underflows, stage 1
  // sees 0 against its bound 3μ): x = 2^-601 (t = 1/2, the winner, at j), x = −2^-601 (t = −1/2, behind, at
  // (j + 3) mod n), x = 2^-590 (t = 2^10, at (j + 5) mod n). The winner's relation needs the exact stage.
  const Ray ray{{0, 0, 0}, {0x1p-600, 0, 0}};
  for (int n = 1; n <= 9; ++n)
    for (int j = 0; j < n; ++j) {
      std::vector<Plane> planes;
      for (int k = 0; k < n; ++k) {
        double x = (k + 2) * 0x1p-600, normal_x = 1;
        if (k == j) {
          x = 0x1p-601, normal_x = 0x1p-600;
        } else if (k == (j + 3) % n) {
          x = -0x1p-601, normal_x = 0x1p-600;
        } else if (k == (j + 5) % n) {
          x = 0x1p-590, normal_x = 0x1p-600;
        }
        planes.push_back({{x, 0, 0}, {normal_x, 0, 0}});
      }
      const std::string context = "n = " + std::to_string(n) + ", j = " + std::to_string(j);
      expect_every_path(ray, planes, hit(static_cast<std::size_t>(j), 0.5), context);
      for (const NamedScreen& s : every_screen())
        EXPECT_EQ(detail::nearest_traced_with_screen(ray, PlaneSet(planes), s.screen).relation_stage, Stage::exact)
            << s.name << ", " << context;
    }
}

TEST(NearestScreen, AnOriginOnAPlaneWinsOverEveryLaterPlane) {
  // Ray o = 0, d = (1, 0, 0); planes x = 2 + k (t = 2 + k), except plane j through the origin with normal
  // (1, 1, 0) (num = 0: t = 0, which stage 1 cannot certify) and plane (j + 4) mod n through the origin with
  // normal (1, 2, 0), another plane tied at t = 0: the smaller of the two indices wins, with t = +0.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  for (int n = 1; n <= 9; ++n)
    for (int j = 0; j < n; ++j) {
      std::vector<Plane> planes;
      const int twin = (j + 4) % n;
      for (int k = 0; k < n; ++k) {
        if (k == j) {
          planes.push_back({{0, 0, 0}, {1, 1, 0}});
        } else if (k == twin) {
          planes.push_back({{0, 0, 0}, {1, 2, 0}});
        } else {
          planes.push_back({{2.0 + k, 0, 0}, {1, 0, 0}});
        }
      }
      expect_every_path(ray, planes, hit(static_cast<std::size_t>(std::min(j, twin)), 0.0),
                        "n = " + std::to_string(n) + ", j = " + std::to_string(j));
    }
}

TEST(NearestScreen, EveryHitAfterTheFirstCountsOneComparison) {
  // Ray o = 0, d = (1, 0, 0), nine planes x = 1..9 (all hits, nearest first, then from far to near:
  // x = 1, 9, 8, ..., 2). Whatever a screen sets aside, the trace counts 8 comparisons, all decided by the
  // filter (the t differ by at least 1); plane 0 wins.
  const Ray ray{{0, 0, 0}, {1, 0, 0}};
  std::vector<Plane> planes = {{{1, 0, 0}, {1, 0, 0}}};
  for (int x = 9; x >= 2; --x) planes.push_back({{static_cast<double>(x), 0, 0}, {1, 0, 0}});
  for (const NamedScreen& s : every_screen()) {
    const TracedNearestHit got = detail::nearest_traced_with_screen(ray, PlaneSet(planes), s.screen);
    EXPECT_EQ(got.hit, hit(0, 1.0)) << s.name;
    EXPECT_EQ(got.comparisons[static_cast<std::size_t>(Stage::filter)], 8u) << s.name;
    EXPECT_EQ(got.comparison_stage, Stage::filter) << s.name;
  }
}

RC_GTEST_PROP(NearestScreenProperty, EveryScreenEqualsBruteForceExactOnLargerScenes, ()) {
  // The generated scenes (exact ties, near ties, coincident twins, duplicates, parallel, behind and hard
  // planes) with up to 40 planes: several groups per screen, ties and uncertain lanes in any lane. Every
  // screen and the scalar loop give the brute-force exact answer, and count one comparison per hit
  // candidate after the first (coincident planes set aside cost none).
  const test_support::PlaneScene scene = *rc::gen::exec([] {
    const testkit::BitSource bits = [] {
      return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max());
    };
    return test_support::make_plane_scene(bits, 40);
  });
  const test_support::OracleNearest expected = test_support::brute_force_nearest(scene.ray, scene.planes);
  const PlaneSet set(scene.planes);
  std::uint32_t hit_candidates = 0;
  for (const std::uint32_t k : set.candidates()) {
    const test_support::ExactTerms e = test_support::exact_terms(scene.ray, scene.planes[k]);
    hit_candidates += e.den != 0 && e.num * e.den >= 0;
  }
  for (const NamedScreen& s : every_screen()) {
    const TracedNearestHit got = detail::nearest_traced_with_screen(scene.ray, set, s.screen);
    RC_ASSERT(got.hit.has_value() == expected.plane.has_value());
    std::uint32_t comparisons = 0;
    for (std::uint32_t c : got.comparisons) comparisons += c;
    RC_ASSERT(comparisons == (hit_candidates == 0 ? 0 : hit_candidates - 1));
    if (!expected.plane) continue;
    RC_ASSERT(got.hit->plane == *expected.plane);
    RC_ASSERT(same_bits(got.hit->t, expected.rounded_t()));
  }
}

// docs/contract.md §8 on a plane set: the nearest hit among the planes whose exact t lies in [t_min, t_max].
// Planes x = 1, 2, 3 and a second x = 2 (index 3); along +x from the origin t = 1, 2, 3; along 3·x, t = 1/3, 2/3, 1.
TEST(NearestHitInterval, HandDerived) {
  const std::vector<Plane> planes{{{1, 0, 0}, {1, 0, 0}}, {{2, 0, 0}, {1, 0, 0}}, {{3, 0, 0}, {-1, 0, 0}},
                                  {{2, 5, 7}, {2, 0, 0}}};
  const PlaneSet set(planes);
  const Ray x{{0, 0, 0}, {1, 0, 0}};
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto plane_of = [&](const Ray& r, double lo, double hi) -> int {
    const std::optional<NearestHit> got = nearest_hit(r, RayInterval{lo, hi}, set);
    const std::optional<NearestHit> want = nearest_hit_exact(r, RayInterval{lo, hi}, planes);
    EXPECT_EQ(got.has_value(), want.has_value()) << lo << " " << hi;
    if (!got || !want) return -1;
    EXPECT_EQ(got->plane, want->plane);
    EXPECT_TRUE(same_bits(got->t, want->t));
    return static_cast<int>(got->plane);
  };
  EXPECT_EQ(plane_of(x, 0, inf), 0);
  EXPECT_EQ(plane_of(x, 1, inf), 0);                        // closed: t = t_min counts
  EXPECT_EQ(plane_of(x, std::nextafter(1.0, 2.0), inf), 1);  // an ulp above t = 1
  EXPECT_EQ(plane_of(x, 2, 2), 1);                          // t = 2 twice: the smaller index
  EXPECT_EQ(plane_of(x, 2.5, 2.75), -1);
  EXPECT_EQ(plane_of(x, 0, std::nextafter(1.0, 0.0)), -1);
  EXPECT_EQ(plane_of(x, 2.5, inf), 2);
  // t = 1/3 is not a double: RN(1/3) < 1/3, so [RN(1/3), inf] holds it and [0, RN(1/3)] does not.
  const Ray x3{{0, 0, 0}, {3, 0, 0}};
  const double third = 1.0 / 3.0;
  EXPECT_EQ(plane_of(x3, third, inf), 0);
  EXPECT_EQ(plane_of(x3, 0, third), -1);
  EXPECT_EQ(plane_of(x3, 0, std::nextafter(third, 1.0)), 0);
  EXPECT_EQ(plane_of(x3, std::nextafter(third, 1.0), inf), 1);
  EXPECT_TRUE(same_bits(nearest_hit(x3, RayInterval{0, inf}, set)->t, third));
  // The whole ray is the nearest hit without an interval.
  EXPECT_EQ(nearest_hit(x, RayInterval{}, set)->plane, nearest_hit(x, set)->plane);
  EXPECT_THROW((void)nearest_hit(x, RayInterval{2, 1}, set), invalid_input);
  EXPECT_THROW((void)nearest_hit_exact(x, RayInterval{-1, 1}, planes), invalid_input);
}

RC_GTEST_PROP(NearestHitIntervalProperty, CertifiedEqualsExactWithBoundsOnAndBesideEveryT, ()) {
  // The generated scenes of up to 40 planes (exact ties, near ties, coincident twins, behind, parallel), with
  // bounds drawn from every plane's rounded t and its neighbours: the exact comparison against a bound is asked
  // where t and the bound are equal or an ulp apart.
  const test_support::PlaneScene scene = *rc::gen::exec([] {
    const testkit::BitSource bits = [] {
      return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max());
    };
    return test_support::make_plane_scene(bits, 40);
  });
  std::vector<double> bounds{0.0, std::numeric_limits<double>::infinity()};
  for (const Plane& p : scene.planes) {
    const Intersection r = intersect(scene.ray, p);
    if (r.relation != Relation::hit || !std::isfinite(r.t)) continue;
    bounds.insert(bounds.end(), {r.t, std::nextafter(r.t, 0.0), std::nextafter(r.t, 2 * r.t + 1)});
  }
  const std::size_t i = *rc::gen::inRange<std::size_t>(0, bounds.size());
  const std::size_t j = *rc::gen::inRange<std::size_t>(0, bounds.size());
  double lo = std::min(bounds[i], bounds[j]), hi = std::max(bounds[i], bounds[j]);
  if (std::isinf(lo)) lo = 0;
  const RayInterval interval{lo, hi};
  const PlaneSet set(scene.planes);
  const std::optional<NearestHit> got = nearest_hit(scene.ray, interval, set);
  const std::optional<NearestHit> want = nearest_hit_exact(scene.ray, interval, scene.planes);
  RC_ASSERT(got.has_value() == want.has_value());
  if (!want) return;
  RC_ASSERT(got->plane == want->plane);
  RC_ASSERT(same_bits(got->t, want->t));
}

}  // namespace
}  // namespace raykernel
