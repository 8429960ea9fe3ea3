// The closest point of a mesh (kernel/include/raykernel/closest_point.hpp, docs/contract.md §11).
//
// - The interval arithmetic of the filter (core/interval.hpp, proved in proofs/core/IntervalWidening.v): every
//   operation's interval holds the exact result, checked in GMP rationals at random, huge, tiny, subnormal and
//   overflowing values; next_up and next_down are IEEE nextUp and nextDown (std::nextafter), bit for bit — the link
//   the proof takes as given.
// - An independent oracle: the squared distance to each triangle by another construction than Ericson's regions
//   (the projection onto the plane when it falls inside the triangle, else the nearest of the three segments,
//   all in GMP rationals), the smallest exact value winning, ties to the smallest index. closest_point (BVH,
//   intervals) and closest_point_exact (brute force, Ericson in rationals) must both give its triangle, its exact
//   squared distance, its point rounded to nearest and √ of it rounded to nearest (MPFR at 200 bits here, then
//   checked against its neighbours exactly).
// - Over the closed test meshes and random soups (shared vertices, degenerate and duplicated triangles) at scales
//   from 2^-1000 to 2^600, for query points at vertices, on edges, inside faces, on the grid around the mesh and
//   moved off the surface along exact offsets; in a hostile floating-point environment too.
// - Hand-derived cases (derivations in the comments) check both paths.
#include <raykernel/closest_point.hpp>
#include <raykernel/fp_environment.hpp>
#include <raykernel/testkit/mesh_rapidcheck.hpp>
#include <raykernel/testkit/meshes.hpp>

#include "core/interval.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <mpfr.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <bit>
#include <cfenv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raykernel {
namespace {

bool same_bits(double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); }

// ---- intervals ---------------------------------------------------------------------------------------------------

using detail::Interval;

bool holds(const Interval& i, const mpq_class& exact) {
  const auto le = [](double x, const mpq_class& q) { return std::isinf(x) ? x < 0 : mpq_class(x) <= q; };
  const auto ge = [](double x, const mpq_class& q) { return std::isinf(x) ? x > 0 : mpq_class(x) >= q; };
  return !std::isnan(i.lo) && !std::isnan(i.hi) && le(i.lo, exact) && ge(i.hi, exact);
}

TEST(ClosestInterval, EveryOperationHoldsTheExactResult) {
  std::mt19937_64 rng(20261129);
  std::uniform_int_distribution<int> exponent(-1080, 1030), mantissa(-(1 << 20), 1 << 20), pick(0, 9);
  const auto draw = [&]() {
    switch (pick(rng)) {
      case 0: return 0.0;
      case 1: return std::numeric_limits<double>::denorm_min() * mantissa(rng);
      case 2: return std::numeric_limits<double>::max() * (mantissa(rng) % 2 == 0 ? 1 : -1);
      default: return std::ldexp(static_cast<double>(mantissa(rng)) + 0.5, exponent(rng) % 1000);
    }
  };
  for (int n = 0; n < 200000; ++n) {
    const double x = draw(), y = draw(), z = draw();
    const Interval a = Interval::point(x), b = Interval::point(y);
    const mpq_class qx(x), qy(y), qz(z);
    ASSERT_TRUE(holds(a + b, qx + qy)) << x << " + " << y;
    ASSERT_TRUE(holds(a - b, qx - qy)) << x << " - " << y;
    ASSERT_TRUE(holds(a * b, qx * qy)) << x << " * " << y;
    ASSERT_TRUE(holds(detail::square(a), qx * qx)) << x << "^2";
    // Intervals of intervals: (x·y + z)·(x − z), where the inner ones may already hold ±inf.
    const Interval c = (a * b + Interval::point(z)) * (a - Interval::point(z));
    ASSERT_TRUE(holds(c, (qx * qy + qz) * (qx - qz))) << x << " " << y << " " << z;
    if (detail::square(b).lo > 0) {  // divide_nonnegative's precondition
      const Interval d = detail::divide_nonnegative(detail::square(a), detail::square(b));
      ASSERT_TRUE(holds(d, (qx * qx) / (qy * qy))) << x << "^2 / " << y << "^2";
    }
  }
  // next_up is IEEE nextUp (Flocq's Bsucc, which proofs/core/IntervalWidening.v takes it to be), bit for bit, on
  // every kind of double: ±0, subnormals, binade boundaries, DBL_MAX, ±inf, and at random.
  std::vector<double> probes = {0.0, -0.0, std::numeric_limits<double>::denorm_min(), -std::numeric_limits<double>::denorm_min(),
                                0x1p-1022, -0x1p-1022, 0x1.fffffffffffffp-1023, 1.0, -1.0, 0x1.fffffffffffffp+1023,
                                -0x1.fffffffffffffp+1023, std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity()};
  std::uniform_int_distribution<std::uint64_t> any_bits;
  for (int n = 0; n < 100000; ++n) {
    const double x = std::bit_cast<double>(any_bits(rng));
    if (!std::isnan(x)) probes.push_back(x);
  }
  for (const double x : probes) {
    ASSERT_TRUE(same_bits(detail::next_up(x), std::nextafter(x, std::numeric_limits<double>::infinity())) ||
                (x == std::numeric_limits<double>::infinity() && detail::next_up(x) == x))
        << std::hexfloat << x;
    ASSERT_TRUE(same_bits(detail::next_down(x), std::nextafter(x, -std::numeric_limits<double>::infinity())) ||
                (x == -std::numeric_limits<double>::infinity() && detail::next_down(x) == x))
        << std::hexfloat << x;
  }
  // One ulp of widening: the smallest steps.
  EXPECT_EQ(detail::next_up(0.0), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(detail::next_up(-0.0), std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(detail::next_down(0.0), -std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(detail::next_up(1.0), 1.0 + 0x1p-52);
  EXPECT_EQ(detail::next_down(1.0), 1.0 - 0x1p-53);
  EXPECT_EQ(detail::next_up(-std::numeric_limits<double>::infinity()), -std::numeric_limits<double>::max());
  EXPECT_EQ(detail::next_up(std::numeric_limits<double>::infinity()), std::numeric_limits<double>::infinity());
  EXPECT_EQ(detail::interval_sign(Interval::point(0)), 0);
  EXPECT_EQ(detail::interval_sign({-1, 1}), detail::interval_uncertain);
}

// ---- the independent oracle ----------------------------------------------------------------------------------------

using Q = mpq_class;
struct QV {
  Q x, y, z;
};
QV qv(const Vec3& v) { return {Q(v.x), Q(v.y), Q(v.z)}; }
QV sub(const QV& a, const QV& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Q qdot(const QV& a, const QV& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
QV qcross(const QV& a, const QV& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
QV axpy(const Q& t, const QV& d, const QV& o) { return {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z}; }

struct OracleMeasure {
  Q d2;
  QV point;
};

// The nearest point of the segment [s0, s1] (a point when s0 = s1).
OracleMeasure on_segment(const QV& p, const QV& s0, const QV& s1) {
  const QV e = sub(s1, s0);
  const Q l2 = qdot(e, e);
  Q t = 0;
  if (l2 > 0) {
    t = qdot(sub(p, s0), e) / l2;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
  }
  const QV q = axpy(t, e, s0);
  const QV r = sub(p, q);
  return {qdot(r, r), q};
}

// The projection onto the plane when it lies in the closed triangle (same side of the three edges as the normal),
// else the nearest of the three segments.
OracleMeasure oracle_triangle(const QV& p, const QV& a, const QV& b, const QV& c) {
  const QV n = qcross(sub(b, a), sub(c, a));
  const Q n2 = qdot(n, n);
  if (n2 > 0) {
    const QV q = axpy(-qdot(sub(p, a), n) / n2, n, p);
    const auto side = [&](const QV& u, const QV& v) { return sgn(qdot(qcross(sub(v, u), sub(q, u)), n)); };
    if (side(a, b) >= 0 && side(b, c) >= 0 && side(c, a) >= 0) {
      const QV r = sub(p, q);
      return {qdot(r, r), q};
    }
  }
  OracleMeasure best = on_segment(p, a, b);
  for (const OracleMeasure& m : {on_segment(p, b, c), on_segment(p, c, a)})
    if (m.d2 < best.d2) best = m;
  return best;
}

struct OracleAnswer {
  std::uint32_t triangle;
  OracleMeasure m;
};
OracleAnswer oracle(const Vec3& query, const Mesh& mesh) {
  const QV p = qv(query);
  OracleAnswer best{0, oracle_triangle(p, qv(mesh.triangle(0).a), qv(mesh.triangle(0).b), qv(mesh.triangle(0).c))};
  for (std::uint32_t k = 1; k < mesh.triangles.size(); ++k) {
    const Triangle t = mesh.triangle(k);
    OracleMeasure m = oracle_triangle(p, qv(t.a), qv(t.b), qv(t.c));
    if (m.d2 < best.m.d2) best = {k, m};
  }
  return best;
}

// RN(q), ties to even, binary64 with gradual underflow: MPFR at 53 bits in binary64's exponent range.
double round_q(const Q& q) {
  const mpfr_exp_t emin = mpfr_get_emin(), emax = mpfr_get_emax();
  mpfr_set_emin(-1073);
  mpfr_set_emax(1024);
  mpfr_t x;
  mpfr_init2(x, 53);
  const int t = mpfr_set_q(x, q.get_mpq_t(), MPFR_RNDN);
  mpfr_subnormalize(x, t, MPFR_RNDN);
  const double d = mpfr_get_d(x, MPFR_RNDN);
  mpfr_clear(x);
  mpfr_set_emin(emin);
  mpfr_set_emax(emax);
  return d;
}

// Whether s = RN(√q): the midpoints m− = (s⁻ + s)/2 and m+ = (s + s⁺)/2 with the neighbours s⁻, s⁺ must satisfy
// m−² ≤ q ≤ m+², ties (q equal to a midpoint's square) going to the even significand. Exact, in rationals.
bool is_rounded_sqrt(double s, const Q& q) {
  if (!(s >= 0) || std::isinf(s)) return false;
  const double up = std::nextafter(s, INFINITY), down = std::nextafter(s, 0.0);
  const Q hi = (Q(s) + Q(up)) / 2, lo = s == 0 ? Q(0) : (Q(s) + Q(down)) / 2;
  const bool even = (std::bit_cast<std::uint64_t>(s) & 1) == 0;
  if (q < lo * lo || q > hi * hi) return false;
  if (s != 0 && q == lo * lo) return even;
  if (q == hi * hi) return even;
  return true;
}

std::string vec(const Vec3& v) {
  char b[128];
  std::snprintf(b, sizeof b, "(%a, %a, %a)", v.x, v.y, v.z);
  return b;
}

// The answer must be the oracle's: triangle, exact squared distance, rounded point, distance.
void expect_oracle(const ClosestPoint& c, const OracleAnswer& o, const std::string& what) {
  const Q d2(c.squared_distance_exact.numerator + "/" + c.squared_distance_exact.denominator);
  RC_ASSERT(c.triangle == o.triangle);
  RC_ASSERT(d2 == o.m.d2);
  if (!same_bits(c.point.x, round_q(o.m.point.x)) || !same_bits(c.point.y, round_q(o.m.point.y)) ||
      !same_bits(c.point.z, round_q(o.m.point.z)))
    RC_FAIL(what + ": point " + vec(c.point));
  RC_ASSERT(same_bits(c.squared_distance, round_q(o.m.d2)));
  if (!is_rounded_sqrt(c.distance, o.m.d2)) RC_FAIL(what + ": distance not RN(√d²)");
}

// ---- meshes and queries --------------------------------------------------------------------------------------------

struct TestMesh {
  std::unique_ptr<PreparedMesh> prepared;
};
const std::vector<TestMesh>& test_meshes() {
  static const std::vector<TestMesh> meshes = [] {
    std::vector<TestMesh> v;
    auto add = [&](Mesh m, BvhBuildOptions o = {}) { v.push_back({std::make_unique<PreparedMesh>(std::move(m), o)}); };
    add(testkit::make_octahedron());
    add(testkit::make_subdivided_cube(2), {.max_leaf_size = 1, .max_leaf_size_hard = 1, .bins = 8});
    add(testkit::make_icosphere(1), {.max_leaf_size = 2, .max_leaf_size_hard = 4, .bins = 16});
    add(testkit::make_terrain(2));
    add(testkit::make_overlapping_fan(7, true));
    add(testkit::make_octahedron(0x1p-1000));
    add(testkit::make_octahedron(0x1p400));
    return v;
  }();
  return meshes;
}

// A query point: a target on the mesh (vertex, edge, face, grid) moved off by an exact small offset (or not).
Vec3 query_point(const Mesh& mesh, const Box3& bounds) {
  Vec3 p = testkit::target_point(mesh, bounds, *rc::gen::inRange(0, 4));
  const double s = std::max({std::fabs(bounds.lo.x), std::fabs(bounds.hi.x), std::fabs(bounds.lo.y),
                             std::fabs(bounds.hi.y), std::fabs(bounds.lo.z), std::fabs(bounds.hi.z), 0x1p-1000});
  switch (*rc::gen::inRange(0, 4)) {
    case 0: break;  // on the surface or the grid
    case 1: {       // a small exact step along the axes
      const auto step = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-3, 4)), -*rc::gen::inRange(2, 12)) * s; };
      const Vec3 moved{p.x + step(), p.y + step(), p.z + step()};
      if (std::isfinite(moved.x) && std::isfinite(moved.y) && std::isfinite(moved.z)) p = moved;
      break;
    }
    default: {  // anywhere around the mesh
      const auto c = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-40, 41)), -4) * s; };
      p = {c(), c(), c()};
    }
  }
  return p;
}

RC_GTEST_PROP(ClosestPoint, AgreesWithTheIndependentOracle, ()) {
  std::unique_ptr<PreparedMesh> own;
  const PreparedMesh* prepared;
  if (*rc::gen::inRange(0, 3) == 0) {
    own = std::make_unique<PreparedMesh>(testkit::random_soup(),
                                         BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4});
    prepared = own.get();
  } else {
    prepared = test_meshes()[*rc::gen::inRange<std::size_t>(0, test_meshes().size())].prepared.get();
  }
  const Mesh& mesh = prepared->mesh();
  for (int n = 0; n < 10; ++n) {
    const Vec3 p = query_point(mesh, prepared->bvh().bounds());
    const OracleAnswer o = oracle(p, mesh);
    const ClosestPoint fast = closest_point(p, *prepared);
    expect_oracle(fast, o, "BVH at " + vec(p));
    const ClosestPoint exact = closest_point_exact(p, mesh);
    expect_oracle(exact, o, "exact at " + vec(p));
    RC_ASSERT(fast.feature == exact.feature);
    RC_ASSERT(fast.corner == exact.corner);
  }
}

// ---- hand-derived cases ----------------------------------------------------------------------------------------------

Mesh one_triangle(const Vec3& a, const Vec3& b, const Vec3& c) { return {{a, b, c}, {{0, 1, 2}}}; }

void expect_both(const Mesh& mesh, const Vec3& p, std::uint32_t triangle, ClosestFeature feature, int corner,
                 const Vec3& point, const std::string& d2, double distance) {
  const PreparedMesh prepared(mesh);
  for (const ClosestPoint& c : {closest_point(p, prepared), closest_point_exact(p, mesh)}) {
    EXPECT_EQ(c.triangle, triangle) << vec(p);
    EXPECT_EQ(c.feature, feature) << vec(p);
    EXPECT_EQ(c.corner, corner) << vec(p);
    EXPECT_TRUE(same_bits(c.point.x, point.x) && same_bits(c.point.y, point.y) && same_bits(c.point.z, point.z))
        << vec(p) << " gave " << vec(c.point);
    EXPECT_EQ(c.squared_distance_exact.str(), d2) << vec(p);
    EXPECT_TRUE(same_bits(c.distance, distance)) << vec(p) << ": " << c.distance;
  }
}

TEST(ClosestPoint, HandDerivedRegionsOfTheUnitTriangle) {
  // The triangle a = (0,0,0), b = (1,0,0), c = (0,1,0) in z = 0.
  const Mesh m = one_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Above the face: the foot (1/4, 1/4, 0), distance 1.
  expect_both(m, {0.25, 0.25, 1}, 0, ClosestFeature::face, 0, {0.25, 0.25, 0}, "1/1", 1.0);
  // Beyond a: the vertex, d² = 1 + 1 = 2, √2 rounded = 0x1.6a09e667f3bcdp+0 (1.4142135623730951).
  expect_both(m, {-1, -1, 0}, 0, ClosestFeature::vertex, 0, {0, 0, 0}, "2/1", 0x1.6a09e667f3bcdp+0);
  // Below ab: the foot (1/2, 0, 0) inside edge ab, d² = 1.
  expect_both(m, {0.5, -1, 0}, 0, ClosestFeature::edge, 0, {0.5, 0, 0}, "1/1", 1.0);
  // Beyond bc: (1, 1, 0) projects to (1/2, 1/2, 0), d² = 1/4 + 1/4 = 1/2, √(1/2) = 0x1.6a09e667f3bcdp-1.
  expect_both(m, {1, 1, 0}, 0, ClosestFeature::edge, 1, {0.5, 0.5, 0}, "1/2", 0x1.6a09e667f3bcdp-1);
  // Left of ca: (−2, 1/2, 3) projects to (0, 1/2, 0), d² = 4 + 9 = 13, √13 = 3.605551275463989.
  expect_both(m, {-2, 0.5, 3}, 0, ClosestFeature::edge, 2, {0, 0.5, 0}, "13/1", 3.605551275463989);
  // Beyond c along y: the vertex (0, 1, 0), d² = 1.
  expect_both(m, {0, 2, 0}, 0, ClosestFeature::vertex, 2, {0, 1, 0}, "1/1", 1.0);
  // On the surface: distance 0, the point itself.
  expect_both(m, {0.125, 0.5, 0}, 0, ClosestFeature::face, 0, {0.125, 0.5, 0}, "0/1", 0.0);
}

TEST(ClosestPoint, HandDerivedInexactFoot) {
  // The triangle (1,0,0), (0,1,0), (0,0,1) and the origin: the foot is the centroid (1/3, 1/3, 1/3), d² = 1/3.
  // RN(1/3) = 0x1.5555555555555p-2; √(1/3) = 0.57735026918962576450... rounds to 0x1.279a74590331cp-1.
  const Mesh m = one_triangle({1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  expect_both(m, {0, 0, 0}, 0, ClosestFeature::face, 0,
              {0x1.5555555555555p-2, 0x1.5555555555555p-2, 0x1.5555555555555p-2}, "1/3", 0x1.279a74590331cp-1);
}

TEST(ClosestPoint, HandDerivedDegenerateTriangles) {
  // Collinear a, b, c on the x axis: the segment [0, 2]. From (3, 1, 0) the nearest point is c = (2, 0, 0),
  // d² = 1 + 1 = 2; from (1/2, 0, 4) it is (1/2, 0, 0) inside ab, d² = 16.
  const Mesh line = one_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0});
  expect_both(line, {3, 1, 0}, 0, ClosestFeature::vertex, 2, {2, 0, 0}, "2/1", 0x1.6a09e667f3bcdp+0);
  expect_both(line, {0.5, 0, 4}, 0, ClosestFeature::edge, 0, {0.5, 0, 0}, "16/1", 4.0);
  // One point three times: the vertex a, d² = 9 + 16 = 25.
  const Mesh point = one_triangle({1, 1, 1}, {1, 1, 1}, {1, 1, 1});
  expect_both(point, {4, 5, 1}, 0, ClosestFeature::vertex, 0, {1, 1, 1}, "25/1", 5.0);
}

TEST(ClosestPoint, TiesGoToTheSmallestIndex) {
  // Three triangles at distance 1/2 from (1/4, 1/4, 1/2): triangle 0 in z = 1, and 1 and 2 (one triangle, the copy
  // reversed) in z = 0. The smallest index wins: the foot (1/4, 1/4, 1) on triangle 0.
  Mesh m{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{3, 4, 5}, {0, 1, 2}, {0, 2, 1}}};
  expect_both(m, {0.25, 0.25, 0.5}, 0, ClosestFeature::face, 0, {0.25, 0.25, 1}, "1/4", 0.5);
  // A corner of the cube [−1, 1]³ shared by several triangles: from (−2, −2, −2) every one of them is at the corner,
  // d² = 3; the first of them in index order wins.
  const Mesh cube = testkit::make_subdivided_cube(1);
  const ClosestPoint c = closest_point({-2, -2, -2}, PreparedMesh(cube));
  const ClosestPoint e = closest_point_exact({-2, -2, -2}, cube);
  EXPECT_EQ(c.triangle, e.triangle);
  EXPECT_EQ(c.feature, ClosestFeature::vertex);
  EXPECT_EQ(c.squared_distance_exact.str(), "3/1");  // from (−1,−1,−1): 1 + 1 + 1
  for (std::uint32_t k = 0; k < c.triangle; ++k) {  // no smaller-index triangle has the corner
    const Triangle t = cube.triangle(k);
    for (const Vec3& v : {t.a, t.b, t.c}) EXPECT_FALSE(v.x == -1 && v.y == -1 && v.z == -1) << k;
  }
}

TEST(ClosestPoint, SignedDistanceFollowsTheExactInside) {
  // The cube [−1, 1]³: from (0, 0, 1/2) the nearest face is z = 1, at 1/2, inside: −1/2. From (0, 0, 3): +2.
  const PreparedMesh cube(testkit::make_subdivided_cube(2));
  EXPECT_EQ(signed_distance({0, 0, 0.5}, cube), -0.5);
  EXPECT_EQ(signed_distance({0, 0, 3}, cube), 2.0);
  EXPECT_EQ(signed_distance({1, 0.25, 0.5}, cube), 0.0);  // on the face x = 1
}

TEST(ClosestPoint, BadInputIsNamed) {
  const PreparedMesh cube(testkit::make_subdivided_cube(1));
  try {
    (void)closest_point({0, std::nan(""), 0}, cube);
    FAIL() << "no throw";
  } catch (const invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("query point y"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)closest_point({0, 0, 0}, Mesh{}), invalid_input);
  EXPECT_THROW((void)closest_point_exact({0, 0, 0}, Mesh{{{0, 0, 0}}, {{0, 0, 1}}}), invalid_input);
}

TEST(ClosestPoint, AnyFloatingPointEnvironmentGivesTheSameAnswer) {
  const PreparedMesh sphere(testkit::make_icosphere(2));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  std::vector<Vec3> points;
  for (int n = 0; n < 300; ++n) points.push_back({u(rng), u(rng), u(rng)});
  std::vector<ClosestPoint> reference;
  for (const Vec3& p : points) reference.push_back(closest_point(p, sphere));
  for (const int mode : {FE_UPWARD, FE_DOWNWARD, FE_TOWARDZERO}) {
    const int saved = std::fegetround();
    std::fesetround(mode);
#if defined(__x86_64__)
    const unsigned csr = _mm_getcsr();
    _mm_setcsr(csr | 0x8040u);  // FTZ and DAZ as well
#endif
    std::vector<ClosestPoint> got;
    for (const Vec3& p : points) got.push_back(closest_point(p, sphere));
#if defined(__x86_64__)
    _mm_setcsr(csr);
#endif
    std::fesetround(saved);
    for (std::size_t k = 0; k < points.size(); ++k) {
      EXPECT_EQ(got[k].triangle, reference[k].triangle);
      EXPECT_EQ(got[k].squared_distance_exact.str(), reference[k].squared_distance_exact.str());
      EXPECT_TRUE(same_bits(got[k].distance, reference[k].distance));
    }
  }
}

TEST(ClosestPoint, TheFilterDecidesMostCandidates) {
  // Random points around a sphere: the intervals settle almost every candidate; rationals are the exception.
  const PreparedMesh sphere(testkit::make_icosphere(3));
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::uint64_t candidates = 0, exact = 0;
  for (int n = 0; n < 2000; ++n) {
    const TracedClosestPoint t = closest_point_traced({u(rng), u(rng), u(rng)}, sphere);
    candidates += t.candidates;
    exact += t.exact_features;
  }
  EXPECT_GT(candidates, 2000u);
  EXPECT_LT(exact * 100, candidates) << exact << " of " << candidates;
}

}  // namespace
}  // namespace raykernel
