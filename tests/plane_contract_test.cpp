// docs/contract.md §1–§2 on hand-derived cases: every expected value is worked out in the comment beside it, from
// den = d·n, num = (p − o)·n and the rounding rules, not taken from any code. Each case runs through
// `intersect` (certified) and `intersect_exact` (reference); where the textbook formula (docs/ray-casting.md §2) in plain doubles
// gets it wrong, the case says so and checks that `intersect_naive` indeed differs.
#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace raykernel {
namespace {

using test_support::same_bits;

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double max_double = std::numeric_limits<double>::max();  // 2^1024 − 2^971
constexpr double min_subnormal = 0x1p-1074;

Ray ray(Vec3 o, Vec3 d) { return {o, d}; }
Plane plane(Vec3 p, Vec3 n) { return {p, n}; }

// Checks both guaranteed paths against the hand-derived answer, bit for bit (signed zeros included).
void expect_answer(const Ray& r, const Plane& p, Relation relation, double t) {
  for (const auto& [name, got] : {std::pair{"certified", intersect(r, p)}, std::pair{"exact", intersect_exact(r, p)}}) {
    EXPECT_EQ(got.relation, relation) << name;
    if (relation == Relation::hit || relation == Relation::behind)
      EXPECT_TRUE(same_bits(got.t, t)) << name << ": t = " << std::hexfloat << got.t << ", expected " << t;
    else
      EXPECT_TRUE(std::isnan(got.t)) << name;
  }
}

// ---- The formula and definitions of docs/ray-casting.md §2 ------------------------------------------------------

TEST(Seed, RayTowardsPlaneHitsAtTheDistanceAlongAUnitDirection) {
  // Plane z = 5 (p = (0,0,5), n = (0,0,1)); ray from the origin along +z. den = 1, num = 5: t = 5, and
  // with a unit direction t is the distance travelled.
  expect_answer(ray({0, 0, 0}, {0, 0, 1}), plane({0, 0, 5}, {0, 0, 1}), Relation::hit, 5.0);
}

TEST(Seed, NonUnitDirectionDividesTheDistance) {
  // d = (0,0,4): den = 4, num = 5, t = 5/4 = 1.25 (distance 5 divided by |d| = 4).
  expect_answer(ray({0, 0, 0}, {0, 0, 4}), plane({0, 0, 5}, {0, 0, 1}), Relation::hit, 1.25);
}

TEST(Seed, NonUnitNormalLeavesTUnchanged) {
  // n = (0,0,-3): den = -3, num = -15, t = 5 (the plane's equation is homogeneous in n).
  expect_answer(ray({0, 0, 0}, {0, 0, 1}), plane({1, 2, 5}, {0, 0, -3}), Relation::hit, 5.0);
}

TEST(Seed, ObliqueRayAndPlane) {
  // o = (1,2,3), d = (1,1,1), p = (4,0,0), n = (1,2,2): den = 1+2+2 = 5,
  // num = (3,-2,-3)·(1,2,2) = 3 − 4 − 6 = −7: t = −7/5 < 0 → behind, t = RN(−1.4) = −1.4 (the double).
  expect_answer(ray({1, 2, 3}, {1, 1, 1}), plane({4, 0, 0}, {1, 2, 2}), Relation::behind, -1.4);
}

// ---- Every relation ---------------------------------------------------------------------------------

TEST(Relations, BehindWhenThePlaneIsBehindTheOrigin) {
  // o = (0,0,10) looking along +z at z = 5: den = 1, num = −5 → behind, t = −5.
  expect_answer(ray({0, 0, 10}, {0, 0, 1}), plane({0, 0, 5}, {0, 0, 1}), Relation::behind, -5.0);
}

TEST(Relations, ParallelWhenTheDirectionLiesInThePlaneButTheOriginDoesNot) {
  // d = (1,0,0) ⟂ n = (0,0,1): den = 0; num = 5 ≠ 0 → parallel.
  expect_answer(ray({0, 0, 0}, {1, 0, 0}), plane({0, 0, 5}, {0, 0, 1}), Relation::parallel, 0);
}

TEST(Relations, InPlaneWhenTheWholeRayLiesInThePlane) {
  // o = (1,2,5) is on z = 5 and d = (1,-1,0) ⟂ n: den = 0, num = 0 → in-plane.
  expect_answer(ray({1, 2, 5}, {1, -1, 0}), plane({0, 0, 5}, {0, 0, 1}), Relation::in_plane, 0);
}

TEST(Relations, OriginOnThePlaneIsAHitAtPlusZero) {
  // o on the plane, d leaving it: num = 0, den = −1 → hit with t = 0; the exact zero is +0 (not 0/−1 = −0).
  expect_answer(ray({3, 4, 5}, {0, 0, -1}), plane({0, 0, 5}, {0, 0, 1}), Relation::hit, 0.0);
}

TEST(Relations, DiagonalInPlaneNeedsExactZeros) {
  // n = (1,1,1), p = (0,0,0); o = (1,-2,1): num = −(1 − 2 + 1) = 0; d = (1,1,-2): den = 0 → in-plane.
  // Neither zero comes from a zero factor, so the filter cannot see it; a later stage must.
  expect_answer(ray({1, -2, 1}, {1, 1, -2}), plane({0, 0, 0}, {1, 1, 1}), Relation::in_plane, 0);
}

// ---- Correct rounding: ties to even, near ties that truncation gets wrong ------------------------------

TEST(Rounding, OneTenthRoundsUpWhereTruncationRoundsDown) {
  // num = 1, den = 10: t = 1/10 = 0x1.9999999999999|9999...p-4; the discarded bits 1001... exceed half an
  // ulp, so RN gives 0x1.999999999999ap-4 (= 0.1), truncation 0x1.9999999999999p-4.
  expect_answer(ray({0, 0, 0}, {10, 0, 0}), plane({1, 0, 0}, {1, 0, 0}), Relation::hit, 0x1.999999999999ap-4);
}

TEST(Rounding, OneThirdRoundsDown) {
  // 1/3 = 0x1.5555555555555|555...p-2: discarded bits 0101... < half → 0x1.5555555555555p-2.
  expect_answer(ray({0, 0, 0}, {3, 0, 0}), plane({1, 0, 0}, {1, 0, 0}), Relation::hit, 0x1.5555555555555p-2);
}

TEST(Rounding, ExactTieGoesToEvenUpward) {
  // den = 2^53, num = p_x − o_x = 2^53 − (−3) = 2^53 + 3: t = 1 + 3·2^-53, exactly halfway between
  // 1 + 2^-52 (odd last bit) and 1 + 2^-51 (even): ties to even → 1 + 2^-51. Truncation gives 1 + 2^-52.
  expect_answer(ray({-3, 0, 0}, {0x1p53, 0, 0}), plane({0x1p53, 0, 0}, {1, 0, 0}), Relation::hit, 0x1.0000000000002p+0);
}

TEST(Rounding, ExactTieGoesToEvenDownward) {
  // num = 2^53 + 1, den = 2^53: t = 1 + 2^-53, halfway between 1 (even) and 1 + 2^-52 → 1.
  expect_answer(ray({-1, 0, 0}, {0x1p53, 0, 0}), plane({0x1p53, 0, 0}, {1, 0, 0}), Relation::hit, 1.0);
}

TEST(Rounding, NearTieJustAboveHalfRoundsUp) {
  // n = (1,1,0), d = (2^53,0,0): den = 2^53. p − o = (2^53 + 1, 2^-27, 0): num = 2^53 + 1 + 2^-27.
  // t = 1 + 2^-53 + 2^-80: above the midpoint 1 + 2^-53 → 1 + 2^-52. Truncation gives 1.
  expect_answer(ray({-1, 0, 0}, {0x1p53, 0, 0}), plane({0x1p53, 0x1p-27, 0}, {1, 1, 0}), Relation::hit,
                0x1.0000000000001p+0);
}

TEST(Rounding, NearTieJustBelowHalfRoundsDown) {
  // As above with p_y − o_y = −2^-27: t = 1 + 2^-53 − 2^-80 → 1.
  expect_answer(ray({-1, 0, 0}, {0x1p53, 0, 0}), plane({0x1p53, -0x1p-27, 0}, {1, 1, 0}), Relation::hit, 1.0);
}

TEST(Rounding, ContractSampleNearTie) {
  // The contract's sample answer 18014398509481991/18014398509481984 = (2^54 + 7)/2^54 = 1 + 1.75·2^-52:
  // between 1 + 2^-52 and 1 + 2^-51, nearer the latter → 1.0000000000000004 = 0x1.0000000000002p+0.
  // Built as den = 2^54, num = 2^54 + 7 (p_x = 2^54, o_x = −7).
  expect_answer(ray({-7, 0, 0}, {0x1p54, 0, 0}), plane({0x1p54, 0, 0}, {1, 0, 0}), Relation::hit, 0x1.0000000000002p+0);
}

// ---- Signed zeros, underflow and overflow of t -------------------------------------------------------

TEST(Underflow, TinyNegativeTRoundsToMinusZero) {
  // num = (0 − 2^-1074)·1 = −2^-1074, den = 2^100: t = −2^-1174, far below half the smallest subnormal
  // → rounds to zero and keeps its sign: behind, t = −0.
  expect_answer(ray({min_subnormal, 0, 0}, {0x1p100, 0, 0}), plane({0, 0, 0}, {1, 0, 0}), Relation::behind, -0.0);
}

TEST(Underflow, TinyPositiveTRoundsToPlusZero) {
  // num = 2^-1074, den = 2^100: hit, t = +0 (a nonzero t, so this is a hit at "0+", not the origin).
  expect_answer(ray({0, 0, 0}, {0x1p100, 0, 0}), plane({min_subnormal, 0, 0}, {1, 0, 0}), Relation::hit, 0.0);
}

TEST(Underflow, HalfTheSmallestSubnormalTiesToZero) {
  // num = 2^-1074, den = 2: t = 2^-1075, halfway between 0 (even) and 2^-1074 (odd) → +0.
  expect_answer(ray({0, 0, 0}, {2, 0, 0}), plane({min_subnormal, 0, 0}, {1, 0, 0}), Relation::hit, 0.0);
}

TEST(Underflow, ThreeQuartersOfTheSmallestSubnormalRoundsUp) {
  // num = 3·2^-1074, den = 4: t = 0.75·2^-1074 > half → 2^-1074.
  expect_answer(ray({0, 0, 0}, {4, 0, 0}), plane({3 * min_subnormal, 0, 0}, {1, 0, 0}), Relation::hit, min_subnormal);
}

TEST(Underflow, SubnormalTieGoesToEven) {
  // num = 3·2^-1074, den = 2: t = 1.5·2^-1074, halfway between 2^-1074 (odd) and 2^-1073 (even) → 2^-1073.
  expect_answer(ray({0, 0, 0}, {2, 0, 0}), plane({3 * min_subnormal, 0, 0}, {1, 0, 0}), Relation::hit, 0x1p-1073);
}

TEST(Overflow, TBeyondTheDoubleRangeIsInfinite) {
  // num = 2^1000, den = 2^-100: t = 2^1100 → +inf; with d reversed, behind and −inf.
  expect_answer(ray({0, 0, 0}, {0x1p-100, 0, 0}), plane({0x1p1000, 0, 0}, {1, 0, 0}), Relation::hit, inf);
  expect_answer(ray({0, 0, 0}, {-0x1p-100, 0, 0}), plane({0x1p1000, 0, 0}, {1, 0, 0}), Relation::behind, -inf);
}

TEST(Overflow, HalfwayAboveTheLargestDoubleOverflows) {
  // p_x − o_x = (2^1024 − 2^971) + 2^970 = 2^1024 − 2^970, den = 1: exactly halfway between the largest
  // double (odd significand) and 2^1024 → ties to even → 2^1024, i.e. +inf (IEEE 754 §4.3.1).
  expect_answer(ray({-0x1p970, 0, 0}, {1, 0, 0}), plane({max_double, 0, 0}, {1, 0, 0}), Relation::hit, inf);
}

TEST(Overflow, JustBelowHalfwayStaysFinite) {
  // num = max + 2^969 < the halfway point → rounds to the largest double.
  expect_answer(ray({-0x1p969, 0, 0}, {1, 0, 0}), plane({max_double, 0, 0}, {1, 0, 0}), Relation::hit, max_double);
}

// ---- Intermediate products that overflow or underflow in binary64 but not exactly ---------------------

TEST(Intermediates, ProductsThatOverflowInDoubles) {
  // d = n = (2^600,0,0), p − o = (2^600,0,0): den = num = 2^1200 (infinite in doubles), t = 1 exactly.
  const Ray r = ray({0, 0, 0}, {0x1p600, 0, 0});
  const Plane p = plane({0x1p600, 0, 0}, {0x1p600, 0, 0});
  expect_answer(r, p, Relation::hit, 1.0);
  EXPECT_TRUE(std::isnan(intersect_naive(r, p).t)) << "naive computes inf/inf";
}

TEST(Intermediates, ProductsThatUnderflowInDoubles) {
  // d = n = (2^-600,0,0), p − o = (2^-600,0,0): den = num = 2^-1200 (zero in doubles), t = 1 exactly.
  // The naive formula sees d·n = 0 and calls the ray parallel (or in-plane).
  const Ray r = ray({0, 0, 0}, {0x1p-600, 0, 0});
  const Plane p = plane({0x1p-600, 0, 0}, {0x1p-600, 0, 0});
  expect_answer(r, p, Relation::hit, 1.0);
  EXPECT_NE(intersect_naive(r, p).relation, Relation::hit);
}

TEST(Intermediates, ToolchainUnderflowExample) {
  // TOOLCHAIN.md: d = (−1.6e−151, 2.0e−319, 0), n = (0, −1.6e−151, −1.6e−151). Exactly,
  // den = 2.0e−319 · (−1.6e−151) < 0 (both products underflow to 0 in doubles). With o = 0 and
  // p = (0,0,−1): num = (−1)(−1.6e−151) = 1.6e−151 > 0, so num/den < 0: behind. The factor 1.6e−151 (the
  // same double) cancels: t = −1/2.0e−319 ≈ −5e318, beyond the double range: −inf.
  const Ray r = ray({0, 0, 0}, {-1.6e-151, 2.0e-319, 0});
  const Plane p = plane({0, 0, -1}, {0, -1.6e-151, -1.6e-151});
  expect_answer(r, p, Relation::behind, -inf);
  EXPECT_EQ(intersect_naive(r, p).relation, Relation::parallel) << "naive: both products underflow to zero";
}

TEST(Intermediates, CancellationThatPlainDoublesLose) {
  // n = (1,1,1), p − o = (1e16, 1, −1e16): num = 1 exactly; in doubles 1e16 + 1 rounds to 1e16 (ties to
  // even), and num comes out 0. d = (0,0,-1)·(-1) gives den = 1, so t = 1; naive says t = 0.
  const Ray r = ray({0, 0, 0}, {0, 0, 1});
  const Plane p = plane({1e16, 1, -1e16}, {1, 1, 1});
  expect_answer(r, p, Relation::hit, 1.0);
  EXPECT_EQ(intersect_naive(r, p).t, 0.0);
}

// ---- Invalid input ------------------------------------------------------------------------------------

void expect_invalid(const Ray& r, const Plane& p, const std::string& reason_fragment) {
  using Entry = Intersection (*)(const Ray&, const Plane&);
  for (const Entry f : {Entry{&intersect}, Entry{&intersect_exact}}) {
    try {
      (void)f(r, p);
      ADD_FAILURE() << "no exception for " << reason_fragment;
    } catch (const invalid_input& e) {
      EXPECT_NE(std::string(e.what()).find(reason_fragment), std::string::npos) << e.what();
    }
  }
  const std::optional<std::string> reason = validate(r, p);
  ASSERT_TRUE(reason.has_value());
  EXPECT_NE(reason->find(reason_fragment), std::string::npos) << *reason;
  EXPECT_THROW((void)intersect_exact_rational(r, p), std::invalid_argument);  // invalid_input is one
}

TEST(InvalidInput, EveryNonFiniteComponentIsNamed) {
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(), inf, -inf};
  const char* field[] = {"ray origin", "ray direction", "plane point", "plane normal"};
  for (double b : bad) {
    for (int f = 0; f < 4; ++f) {
      for (int c = 0; c < 3; ++c) {
        Ray r = ray({0, 0, 0}, {0, 0, 1});
        Plane p = plane({0, 0, 5}, {0, 0, 1});
        Vec3* v[] = {&r.origin, &r.direction, &p.point, &p.normal};
        (c == 0 ? v[f]->x : c == 1 ? v[f]->y : v[f]->z) = b;
        expect_invalid(r, p, std::string(field[f]) + " " + "xyz"[c]);
      }
    }
  }
}

TEST(InvalidInput, ZeroDirectionIncludingNegativeZeros) {
  expect_invalid(ray({1, 2, 3}, {0, -0.0, 0}), plane({0, 0, 5}, {0, 0, 1}), "ray direction is the zero vector");
}

TEST(InvalidInput, ZeroNormalIncludingNegativeZeros) {
  expect_invalid(ray({1, 2, 3}, {0, 0, 1}), plane({0, 0, 5}, {-0.0, 0, -0.0}), "plane normal is the zero vector");
}

TEST(InvalidInput, InvalidInputIsAnInvalidArgument) {
  static_assert(std::is_base_of_v<std::invalid_argument, invalid_input>);
  EXPECT_THROW((void)intersect(ray({0, 0, 0}, {0, 0, 0}), plane({0, 0, 0}, {0, 0, 1})), std::invalid_argument);
}

TEST(InvalidInput, TinyButNonzeroVectorsAreValid) {
  // A subnormal direction is not the zero vector: d = (2^-1074,0,0), n = (1,0,0), num = 1:
  // t = 2^1074 → +inf.
  expect_answer(ray({0, 0, 0}, {min_subnormal, 0, 0}), plane({1, 0, 0}, {1, 0, 0}), Relation::hit, inf);
}

// ---- The exact rational t ----------------------------------------------------------------------------

TEST(ExactRational, TIsReportedInLowestTerms) {
  // num = 6, den = 4 → t = 3/2; num and den themselves as reduced rationals.
  const ExactIntersection e = intersect_exact_rational(ray({0, 0, 0}, {4, 0, 0}), plane({6, 0, 0}, {1, 0, 0}));
  ASSERT_TRUE(e.t.has_value());
  EXPECT_EQ(e.t->str(), "3/2");
  EXPECT_EQ(e.num.str(), "6/1");
  EXPECT_EQ(e.den.str(), "4/1");
  EXPECT_EQ(e.intersection.t, 1.5);
}

TEST(ExactRational, NegativeAndDyadic) {
  // o = (0.5,0,0), p = 0, n = (1,0,0), d = (0.75,0,0): num = −1/2, den = 3/4, t = −2/3.
  const ExactIntersection e = intersect_exact_rational(ray({0.5, 0, 0}, {0.75, 0, 0}), plane({0, 0, 0}, {1, 0, 0}));
  ASSERT_TRUE(e.t.has_value());
  EXPECT_EQ(e.t->str(), "-2/3");
  EXPECT_EQ(e.num.str(), "-1/2");
  EXPECT_EQ(e.den.str(), "3/4");
  EXPECT_EQ(e.intersection.relation, Relation::behind);
  EXPECT_EQ(e.intersection.t, -0x1.5555555555555p-1);  // −(2/3) rounds like 2/3: ...5555|5 → down
}

TEST(ExactRational, ZeroTIsZeroOverOne) {
  const ExactIntersection e = intersect_exact_rational(ray({3, 4, 5}, {0, 0, -1}), plane({0, 0, 5}, {0, 0, 1}));
  ASSERT_TRUE(e.t.has_value());
  EXPECT_EQ(e.t->str(), "0/1");
}

TEST(ExactRational, NoTForParallelOrInPlane) {
  EXPECT_FALSE(intersect_exact_rational(ray({0, 0, 0}, {1, 0, 0}), plane({0, 0, 5}, {0, 0, 1})).t.has_value());
  EXPECT_FALSE(intersect_exact_rational(ray({0, 0, 5}, {1, 0, 0}), plane({0, 0, 5}, {0, 0, 1})).t.has_value());
}

TEST(Naive, IsTheSeedFormulaInDoubles) {
  // t = −((o − p)·n)/(d·n) in doubles: o = (1,2,3), p = (4,0,0), n = (1,2,2), d = (1,1,1):
  // −(−3·1 + 2·2 + 3·2)/5 = −7/5 = −1.4 rounded; here no rounding differs from the exact answer.
  const Intersection r = intersect_naive(ray({1, 2, 3}, {1, 1, 1}), plane({4, 0, 0}, {1, 2, 2}));
  EXPECT_EQ(r.relation, Relation::behind);
  EXPECT_EQ(r.t, -1.4);
}

TEST(Version, IsTheProjectVersion) { EXPECT_EQ(version(), "0.1.0"); }

}  // namespace
}  // namespace raykernel
