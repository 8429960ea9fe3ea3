// docs/contract.md §6 on hand-derived cases: every expected value is worked out in the comment beside it from
// N = (b − a) × (c − a), den = d·N, num = (a − o)·N, π(p, q) = d·((p − o) × (q − o)) and the rounding rules, not
// taken from any code. Each case runs through `intersect` (certified) and `intersect_exact` (reference) under
// the rule given, bit for bit (signed zeros included); `relation` must agree.
//
// Most cases use the unit right triangle a = (0,0,0), b = (1,0,0), c = (0,1,0): N = (0,0,1), and for a ray
// o = (x, y, z0), d = (0, 0, 1): den = 1, num = −z0, the crossing point (x, y, 0) and barycentric coordinates
// (πa, πb, πc)/den = (1 − x − y, x, y) (the weights of a, b, c at that point). Tie-break vectors d × (q − p)
// with d = (0,0,1) and q − p = (qx, qy, 0): (−qy, qx, 0) (for p → q; cross product (d_y e_z − d_z e_y, d_z e_x −
// d_x e_z, d_x e_y − d_y e_x)):
//   πc, edge a → b, q − p = (1, 0, 0):   (0, 1, 0)    → +1 (the y component; x is 0)
//   πa, edge b → c, q − p = (−1, 1, 0):  (−1, −1, 0)  → −1
//   πb, edge c → a, q − p = (0, −1, 0):  (1, 0, 0)    → +1
// so with den = +1 the owned rule keeps edges ab and ca and vertex a, and gives away edge bc and vertices b, c.
#include "support/oracle.hpp"

#include <raykernel/triangle.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace raykernel {
namespace {

using test_support::same_bits;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

const Triangle unit{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
Ray up_from(double x, double y, double z0 = -1) { return {{x, y, z0}, {0, 0, 1}}; }

struct Expected {
  TriangleRelation relation;
  TriangleLocation location;
  bool owned;
  double t;
  double ua, ub, uc;
};

void expect_same(const TriangleIntersection& got, const Expected& want, const std::string& what) {
  EXPECT_EQ(got.relation, want.relation) << what << ": " << to_string(got.relation);
  EXPECT_EQ(got.location, want.location) << what << ": " << to_string(got.location);
  EXPECT_EQ(got.owned, want.owned) << what;
  const double g[4] = {got.t, got.barycentric[0], got.barycentric[1], got.barycentric[2]};
  const double w[4] = {want.t, want.ua, want.ub, want.uc};
  for (int k = 0; k < 4; ++k) {
    if (std::isnan(w[k]))
      EXPECT_TRUE(std::isnan(g[k])) << what << ": value " << k;
    else
      EXPECT_TRUE(same_bits(g[k], w[k])) << what << ": value " << k << " is " << std::hexfloat << g[k]
                                         << ", expected " << w[k];
  }
}

// Both guaranteed paths, and the relation-only form, against the hand-derived answer.
void expect_answer(const Ray& r, const Triangle& tri, TriangleRule rule, const Expected& want) {
  const TriangleOptions options{rule, true, true};
  expect_same(intersect(r, tri, options), want, std::string("certified, ") + std::string(to_string(rule)));
  expect_same(intersect_exact(r, tri, options), want, std::string("exact, ") + std::string(to_string(rule)));
  const TriangleClassification c = relation(r, tri, rule);
  EXPECT_EQ(c.relation, want.relation) << "relation()";
  EXPECT_EQ(c.location, want.location) << "relation()";
  EXPECT_EQ(c.owned, want.owned) << "relation()";
}

// ---- Locations and rules on the unit triangle ---------------------------------------------------------------

TEST(TriangleLocations, Inside) {
  // (1/4, 1/4): t = 1, barycentric (1/2, 1/4, 1/4), all π > 0 = den's sign: inside, owned.
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(0.25, 0.25), unit, rule,
                  {TriangleRelation::hit, TriangleLocation::inside, true, 1.0, 0.5, 0.25, 0.25});
}

TEST(TriangleLocations, EdgeAbIsOwned) {
  // (1/2, 0): πc = y = 0, πa = 1/2, πb = 1/2: edge ab; πc's tie-break is +1 = den's: owned, hit under both.
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(0.5, 0), unit, rule,
                  {TriangleRelation::hit, TriangleLocation::edge_ab, true, 1.0, 0.5, 0.5, 0.0});
}

TEST(TriangleLocations, EdgeBcIsGivenAway) {
  // (1/2, 1/2): πa = 1 − 1/2 − 1/2 = 0: edge bc; πa's tie-break is −1: the owned rule misses, closed hits.
  const Expected closed{TriangleRelation::hit, TriangleLocation::edge_bc, false, 1.0, 0.0, 0.5, 0.5};
  Expected owned = closed;
  owned.relation = TriangleRelation::miss;
  expect_answer(up_from(0.5, 0.5), unit, TriangleRule::closed, closed);
  expect_answer(up_from(0.5, 0.5), unit, TriangleRule::owned, owned);
}

TEST(TriangleLocations, EdgeCaIsOwned) {
  // (0, 3/4): πb = x = 0: edge ca; tie-break +1: owned. Barycentric (1/4, 0, 3/4).
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(0, 0.75), unit, rule,
                  {TriangleRelation::hit, TriangleLocation::edge_ca, true, 1.0, 0.25, 0.0, 0.75});
}

TEST(TriangleLocations, VertexAIsOwned) {
  // (0, 0): πb = πc = 0, both tie-breaks +1: vertex a, owned. Barycentric (1, 0, 0).
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(0, 0), unit, rule,
                  {TriangleRelation::hit, TriangleLocation::vertex_a, true, 1.0, 1.0, 0.0, 0.0});
}

TEST(TriangleLocations, VerticesBAndCAreGivenAway) {
  // b = (1, 0): πc = πa = 0, πa's tie-break −1: not owned. c = (0, 1): πa = πb = 0, πa's tie-break −1.
  expect_answer(up_from(1, 0), unit, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::vertex_b, false, 1.0, 0.0, 1.0, 0.0});
  expect_answer(up_from(1, 0), unit, TriangleRule::closed,
                {TriangleRelation::hit, TriangleLocation::vertex_b, false, 1.0, 0.0, 1.0, 0.0});
  expect_answer(up_from(0, 1), unit, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::vertex_c, false, 1.0, 0.0, 0.0, 1.0});
  expect_answer(up_from(0, 1), unit, TriangleRule::closed,
                {TriangleRelation::hit, TriangleLocation::vertex_c, false, 1.0, 0.0, 0.0, 1.0});
}

TEST(TriangleLocations, Outside) {
  // (1, 1): barycentric (−1, 1, 1): πa < 0 opposite to den: outside, a miss under both rules; t = 1 still.
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(1, 1), unit, rule,
                  {TriangleRelation::miss, TriangleLocation::outside, false, 1.0, -1.0, 1.0, 1.0});
  // (−1/2, 1/4): πb = x < 0: outside, barycentric (1 + 1/2 − 1/4, −1/2, 1/4) = (5/4, −1/2, 1/4).
  expect_answer(up_from(-0.5, 0.25), unit, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::outside, false, 1.0, 1.25, -0.5, 0.25});
}

TEST(TriangleLocations, OnTheLineOfAnEdgeButOutside) {
  // (2, 0): πc = 0 but πa = 1 − 2 = −1 < 0: outside (not edge ab), barycentric (−1, 2, 0).
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
    expect_answer(up_from(2, 0), unit, rule,
                  {TriangleRelation::miss, TriangleLocation::outside, false, 1.0, -1.0, 2.0, 0.0});
}

TEST(TriangleLocations, FromTheOtherSideTheOwnedEdgesStay) {
  // o = (x, y, 1), d = (0, 0, −1): den = −1, num = (a − o)·N = −1, t = 1; π = den·barycentric, so the π's
  // have den's sign inside. Tie-breaks with d = (0,0,−1) are the negatives of those above: ab → −1 = den's
  // sign (owned), bc → +1 (not owned). So each edge belongs to the same triangle whichever side the ray
  // comes from.
  const Ray down_ab{{0.5, 0, 1}, {0, 0, -1}}, down_bc{{0.5, 0.5, 1}, {0, 0, -1}};
  expect_answer(down_ab, unit, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::edge_ab, true, 1.0, 0.5, 0.5, 0.0});
  expect_answer(down_bc, unit, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::edge_bc, false, 1.0, 0.0, 0.5, 0.5});
}

TEST(TriangleRules, TheNeighbourAcrossAnEdgeGetsTheOtherHalf) {
  // The triangle (b, a, c') with c' = (0, −1, 0) shares edge ab, oriented b → a: N' = (a − b) × (c' − b) =
  // (−1,0,0) × (−1,−1,0) = (0, 0, 1), den = 1. Through (1/2, 0): its π for the edge b → a is 0 with
  // tie-break d × (a − b) = (0, −1, 0) → −1: not owned. Exactly one of the two triangles owns the hit.
  const Triangle neighbour{{1, 0, 0}, {0, 0, 0}, {0, -1, 0}};
  const TriangleIntersection mine = intersect(up_from(0.5, 0), unit);
  const TriangleIntersection theirs = intersect(up_from(0.5, 0), neighbour);
  EXPECT_TRUE(mine.owned);
  EXPECT_FALSE(theirs.owned);
  // In the neighbour the edge b → a is its edge ab (a' = b, b' = a): location edge-ab, weights (1/2, 1/2, 0).
  expect_answer(up_from(0.5, 0), neighbour, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::edge_ab, false, 1.0, 0.5, 0.5, 0.0});
}

// ---- Relations ---------------------------------------------------------------------------------------------

TEST(TriangleRelations, BehindTheOrigin) {
  // o = (1/4, 1/4, 1), d = (0, 0, 1): num = (a − o)·N = −1, den = 1, t = −1 < 0: behind.
  expect_answer(up_from(0.25, 0.25, 1), unit, TriangleRule::owned,
                {TriangleRelation::behind, TriangleLocation::inside, true, -1.0, 0.5, 0.25, 0.25});
}

TEST(TriangleRelations, OriginOnTheTriangleIsAHitAtPlusZero) {
  // o = (1/4, 1/4, 0): num = 0 exactly, t = +0: hit.
  expect_answer(up_from(0.25, 0.25, 0), unit, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, 0.0, 0.5, 0.25, 0.25});
}

TEST(TriangleRelations, ParallelAndCoplanar) {
  // d = (1, 0, 0): den = d·N = 0. From o = (0, 0, −1): num = 1 ≠ 0: parallel. From o = (−1, 1/4, 0): num = 0:
  // the line lies in the plane (and crosses the triangle): coplanar, never a hit.
  const Expected parallel{TriangleRelation::parallel, TriangleLocation::none, false, nan, nan, nan, nan};
  const Expected coplanar{TriangleRelation::coplanar, TriangleLocation::none, false, nan, nan, nan, nan};
  for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
    expect_answer({{0, 0, -1}, {1, 0, 0}}, unit, rule, parallel);
    expect_answer({{-1, 0.25, 0}, {1, 0, 0}}, unit, rule, coplanar);
  }
}

TEST(TriangleRelations, DegenerateByCollinearOrRepeatedVertices) {
  // Collinear: b − a = (1,1,1), c − a = (2,2,2): N = 0. Repeated: a = b, N = 0·(c − a) = 0. Never a hit, even for
  // a ray through the segment.
  const Expected degenerate{TriangleRelation::degenerate, TriangleLocation::none, false, nan, nan, nan, nan};
  const Ray through_segment{{1, 1, 0}, {0, 0, 1}};
  expect_answer(through_segment, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}, TriangleRule::owned, degenerate);
  expect_answer(through_segment, {{1, 1, 1}, {1, 1, 1}, {0, 3, 1}}, TriangleRule::closed, degenerate);
  expect_answer(through_segment, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, TriangleRule::owned, degenerate);
}

// ---- Rounding ----------------------------------------------------------------------------------------------

TEST(TriangleRounding, ThirdsRoundToNearest) {
  // d = (0, 0, 3): den = 3, num = 1: t = 1/3 → RN = 0x1.5555555555555p-2 (1/3 = 0x1.5555...p-2, the 54th bit
  // and beyond 0101... < half: rounds down). The point o + t·d = (1/4, 1/4, 0): barycentric (1/2, 1/4, 1/4).
  expect_answer({{0.25, 0.25, -1}, {0, 0, 3}}, unit, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, 0x1.5555555555555p-2, 0.5, 0.25, 0.25});
}

TEST(TriangleRounding, TiesGoToEven) {
  // Plane z = 1 + 2^-52, o_z = −2^-53: num = 1 + 2^-52 + 2^-53 = 1 + 3·2^-53 exactly, den = 1. t lies halfway
  // between 1 + 2^-52 (odd significand) and 1 + 2^-51 (even): RN = 1 + 2^-51.
  const double z = 1 + 0x1p-52;
  const Triangle high{{0, 0, z}, {1, 0, z}, {0, 1, z}};
  expect_answer({{0.25, 0.25, -0x1p-53}, {0, 0, 1}}, high, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, 1 + 0x1p-51, 0.5, 0.25, 0.25});
}

TEST(TriangleRounding, EachBarycentricCoordinateIsRoundedOnItsOwn) {
  // Crossing point (x, y) = (0.1, 0.2) as doubles X = 0x1.999999999999ap-4, Y = 0x1.999999999999ap-3, den = 1:
  // barycentric (1 − X − Y, X, Y). X and Y are doubles, so UB = X, UC = Y exactly. 1 − X − Y: X = 0.1 + 2^-56·0.4
  // ... exactly X = 3602879701896397·2^-55, Y = 3602879701896397·2^-54, so X + Y = 10808639105689191·2^-55 and
  // 1 − X − Y = (36028797018963968 − 10808639105689191)·2^-55 = 25220157913274777·2^-55. That needs 55 bits:
  // 25220157913274777 = 4·6305039478318694 + 1, so it lies 1/4 of an ulp (2^-53 here) above
  // 6305039478318694·2^-53 = 0x1.6666666666666p-1: RN = 0x1.6666666666666p-1.
  expect_answer(up_from(0.1, 0.2), unit, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, 1.0, 0x1.6666666666666p-1, 0.1, 0.2});
}

TEST(TriangleRounding, TinyTrianglesWhoseProductsUnderflow) {
  // Everything but d scaled by s = 2^-1000: π, num scale by s², den by s², num by s³: t = s·1 = 2^-1000 (a
  // normal double), barycentric unchanged (1/2, 1/4, 1/4). In binary64 every product (≈ 2^-2000) underflows
  // to 0, so Möller–Trumbore sees det = 0.
  const double s = 0x1p-1000;
  const Triangle tiny{{0, 0, 0}, {s, 0, 0}, {0, s, 0}};
  const Ray ray{{0.25 * s, 0.25 * s, -s}, {0, 0, 1}};
  expect_answer(ray, tiny, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, s, 0.5, 0.25, 0.25});
  EXPECT_NE(intersect_naive(ray, tiny).relation, TriangleRelation::hit);
}

TEST(TriangleRounding, HugeTrianglesWhoseProductsOverflow) {
  // Scaled by s = 2^600 (d unscaled): products ≈ 2^1200 overflow binary64; t = 2^600, barycentric unchanged.
  const double s = 0x1p600;
  const Triangle huge{{0, 0, 0}, {s, 0, 0}, {0, s, 0}};
  const Ray ray{{0.25 * s, 0.25 * s, -s}, {0, 0, 1}};
  expect_answer(ray, huge, TriangleRule::owned,
                {TriangleRelation::hit, TriangleLocation::inside, true, s, 0.5, 0.25, 0.25});
  EXPECT_FALSE(intersect_naive(ray, huge).relation == TriangleRelation::hit &&
               intersect_naive(ray, huge).t == s);
}

TEST(TriangleRounding, ANonzeroCoordinateThatRoundsToZeroKeepsItsSign) {
  // a = (0,0,0), b = (2^60, 0, 0), c = (0, 1, 0): N = (0, 0, 2^60); o = (−2^-1074, 1/2, −1), d = (0, 0, 1):
  // den = 2^60, num = 2^60, t = 1. The crossing point (−2^-1074, 1/2, 0) = ua·a + ub·b + uc·c gives
  // ub = −2^-1074/2^60 = −2^-1134, uc = 1/2, ua = 1/2 + 2^-1134. RN: ua = 1/2, ub = −0 (nonzero, below half the
  // smallest subnormal: keeps its sign), uc = 1/2. πb = den·ub < 0: outside, a miss.
  const Triangle long_edge{{0, 0, 0}, {0x1p60, 0, 0}, {0, 1, 0}};
  expect_answer(up_from(-0x1p-1074, 0.5), long_edge, TriangleRule::owned,
                {TriangleRelation::miss, TriangleLocation::outside, false, 1.0, 0.5, -0.0, 0.5});
}

// ---- Options, exact values, validation, the naive baseline ------------------------------------------------

TEST(TriangleOptionsTest, OnlyWhatIsAskedForIsRounded) {
  const Ray r = up_from(0.25, 0.25);
  const TriangleIntersection only_t = intersect(r, unit, {TriangleRule::owned, true, false});
  EXPECT_EQ(only_t.t, 1.0);
  EXPECT_TRUE(std::isnan(only_t.barycentric[0]) && std::isnan(only_t.barycentric[1]) &&
              std::isnan(only_t.barycentric[2]));
  const TriangleIntersection only_b = intersect(r, unit, {TriangleRule::owned, false, true});
  EXPECT_TRUE(std::isnan(only_b.t));
  EXPECT_EQ(only_b.barycentric[0], 0.5);
  const TriangleIntersection none = intersect(r, unit, {TriangleRule::owned, false, false});
  EXPECT_EQ(none.relation, TriangleRelation::hit);
  EXPECT_EQ(none.location, TriangleLocation::inside);
  EXPECT_TRUE(std::isnan(none.t));
}

TEST(TriangleExactValues, RationalsInLowestTerms) {
  // d = (0,0,3), o = (1/4, 1/4, −1): den = 3, num = 1, π = den·(1/2, 1/4, 1/4) = (3/2, 3/4, 3/4),
  // t = 1/3, barycentric 1/2, 1/4, 1/4.
  const ExactTriangleIntersection x = intersect_exact_rational({{0.25, 0.25, -1}, {0, 0, 3}}, unit);
  EXPECT_EQ(x.den.str(), "3/1");
  EXPECT_EQ(x.num.str(), "1/1");
  EXPECT_EQ(x.pi_a.str(), "3/2");
  EXPECT_EQ(x.pi_b.str(), "3/4");
  EXPECT_EQ(x.pi_c.str(), "3/4");
  ASSERT_TRUE(x.t.has_value() && x.barycentric.has_value());
  EXPECT_EQ(x.t->str(), "1/3");
  EXPECT_EQ((*x.barycentric)[0].str(), "1/2");
  EXPECT_EQ((*x.barycentric)[1].str(), "1/4");
  EXPECT_EQ((*x.barycentric)[2].str(), "1/4");
  // den = 0: no t.
  const ExactTriangleIntersection p = intersect_exact_rational({{0, 0, -1}, {1, 0, 0}}, unit);
  EXPECT_EQ(p.intersection.relation, TriangleRelation::parallel);
  EXPECT_FALSE(p.t.has_value());
  EXPECT_EQ(p.num.str(), "1/1");
}

TEST(TriangleValidation, NonFiniteComponentsAndZeroDirection) {
  const Triangle bad_b{{0, 0, 0}, {1, nan, 0}, {0, 1, 0}};
  const Ray r = up_from(0.25, 0.25);
  EXPECT_EQ(validate(r, bad_b), std::optional<std::string>("triangle vertex b y is NaN"));
  EXPECT_EQ(validate({{0, 0, 0}, {0, 0, 0}}, unit), std::optional<std::string>("ray direction is the zero vector"));
  EXPECT_EQ(validate({{0, -HUGE_VAL, 0}, {0, 0, 1}}, unit), std::optional<std::string>("ray origin y is -inf"));
  EXPECT_FALSE(validate(r, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}).has_value()) << "a degenerate triangle is valid";
  EXPECT_THROW((void)intersect(r, bad_b), invalid_input);
  EXPECT_THROW((void)intersect_exact(r, bad_b), invalid_input);
  EXPECT_THROW((void)relation(r, bad_b), invalid_input);
  EXPECT_THROW((void)intersect({{0, 0, 0}, {0, 0, 0}}, unit), invalid_input);
  try {
    (void)intersect(r, bad_b);
  } catch (const invalid_input& e) {
    EXPECT_STREQ(e.what(), "triangle vertex b y is NaN");
  }
}

TEST(TriangleNaive, MollerTrumboreOnPlainCases) {
  // Inside (1/4, 1/4): u = 1/4, v = 1/4, w = 1/2, t = 1, all exact in doubles.
  const TriangleIntersection n = intersect_naive(up_from(0.25, 0.25), unit);
  EXPECT_EQ(n.relation, TriangleRelation::hit);
  EXPECT_EQ(n.location, TriangleLocation::inside);
  EXPECT_EQ(n.t, 1.0);
  EXPECT_EQ(n.barycentric[0], 0.5);
  EXPECT_EQ(n.barycentric[1], 0.25);
  EXPECT_EQ(n.barycentric[2], 0.25);
  // Edge bc at (1/2, 1/2): u = v = 1/2, u + v = 1: its closed test hits (where the owned rule gives it away).
  EXPECT_EQ(intersect_naive(up_from(0.5, 0.5), unit).relation, TriangleRelation::hit);
  // d = (1, 0, 0): det = 0: parallel from (0, 0, −1).
  EXPECT_EQ(intersect_naive({{0, 0, -1}, {1, 0, 0}}, unit).relation, TriangleRelation::parallel);
  EXPECT_EQ(intersect_naive({{1, 1, 0}, {0, 0, 1}}, {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}).relation,
            TriangleRelation::degenerate);
}

TEST(TriangleStrings, Names) {
  EXPECT_EQ(to_string(TriangleRelation::coplanar), "coplanar");
  EXPECT_EQ(to_string(TriangleLocation::edge_ca), "edge-ca");
  EXPECT_EQ(to_string(TriangleLocation::vertex_b), "vertex-b");
  EXPECT_EQ(to_string(TriangleRule::closed), "closed");
}

}  // namespace
}  // namespace raykernel
