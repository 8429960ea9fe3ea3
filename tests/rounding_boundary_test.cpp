// Roundings at the boundaries (core/quotient_boundary.hpp in both cascades): a quotient on a rounding boundary or
// just above a power of two — which round_quotient's enclosures cannot certify — is decided in expansions, so
// that GMP (the exact stage) is reached only where expansions are not exact. Checked on the contract samples (no
// query whose inputs' exponents all lie in [−400, 400] reaches the exact stage, relation or rounding) and on the
// testkit's above-power-of-two and rounding-tie kinds; every value against the exact path.
#include <raykernel/plane.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel {
namespace {

// The numbers of a sample line, or nothing (a comment, a blank line, a malformed or non-finite field: the
// samples' invalid lines, which never reach a cascade).
std::optional<std::vector<double>> numbers(const std::string& line, std::size_t count) {
  if (line.empty() || line[0] == '#') return std::nullopt;
  std::istringstream in(line);
  std::vector<double> x;
  std::string token;
  while (in >> token) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (*end != '\0' || !std::isfinite(v) || errno == ERANGE) return std::nullopt;
    x.push_back(v);
  }
  if (x.size() != count) return std::nullopt;
  return x;
}

// Whether every nonzero input has its binary exponent in [−400, 400].
bool exponents_in_range(const std::vector<double>& x) {
  for (double v : x) {
    if (v == 0) continue;
    int e = 0;
    std::frexp(v, &e);
    if (e < -400 || e > 400) return false;
  }
  return true;
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Checks the certified answer against the exact path, and that no stage was the exact one.
void check_triangle(const Ray& ray, const Triangle& triangle, TriangleRule rule, const std::string& where) {
  if (validate(ray, triangle).has_value()) return;
  const TracedTriangleIntersection c = intersect_traced(ray, triangle, {rule, true, true});
  const TriangleIntersection e = intersect_exact(ray, triangle, {rule, true, true});
  const bool gmp = c.relation_stage == Stage::exact || c.rounding_stage == Stage::exact;
  EXPECT_FALSE(gmp) << where;
  EXPECT_EQ(c.intersection.relation, e.relation) << where;
  EXPECT_TRUE(same(c.intersection.t, e.t) || (std::isnan(c.intersection.t) && std::isnan(e.t))) << where;
  for (int k = 0; k < 3; ++k)
    EXPECT_TRUE(same(c.intersection.barycentric[k], e.barycentric[k]) ||
                (std::isnan(c.intersection.barycentric[k]) && std::isnan(e.barycentric[k])))
        << where << " coordinate " << k;
}

// With `without_gmp` false, the exact stage is allowed; returns whether it was reached.
bool check_plane(const Ray& ray, const Plane& plane, const std::string& where, bool without_gmp = true) {
  if (validate(ray, plane).has_value()) return false;
  const TracedIntersection c = intersect_traced(ray, plane);
  const Intersection e = intersect_exact(ray, plane);
  const bool gmp = c.relation_stage == Stage::exact || c.t_stage == Stage::exact;
  if (without_gmp) EXPECT_FALSE(gmp) << where;
  EXPECT_EQ(c.intersection.relation, e.relation) << where;
  EXPECT_TRUE(same(c.intersection.t, e.t) || (std::isnan(c.intersection.t) && std::isnan(e.t))) << where;
  return gmp;
}

TEST(RoundingBoundary, TriangleSampleNeverReachesGmpInRange) {
  int checked = 0;
  const std::vector<std::string> lines = lines_of(std::string(RAYKERNEL_CASES_DIR) + "/triangle-sample.txt");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto x = numbers(lines[i], 15);
    if (!x || !exponents_in_range(*x)) continue;
    const auto& v = *x;
    const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    const Triangle triangle{{v[6], v[7], v[8]}, {v[9], v[10], v[11]}, {v[12], v[13], v[14]}};
    for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
      check_triangle(ray, triangle, rule, "triangle-sample.txt:" + std::to_string(i + 1));
    ++checked;
  }
  EXPECT_GT(checked, 300);  // the sample's lines in range (the others have extreme exponents or are invalid)
}

TEST(RoundingBoundary, ClassifySampleNeverReachesGmpInRange) {
  int checked = 0;
  const std::vector<std::string> lines = lines_of(std::string(RAYKERNEL_CASES_DIR) + "/classify-sample.txt");
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const auto x = numbers(lines[i], 12);
    if (!x || !exponents_in_range(*x)) continue;
    const auto& v = *x;
    check_plane(Ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}}, Plane{{v[6], v[7], v[8]}, {v[9], v[10], v[11]}},
                             "classify-sample.txt:" + std::to_string(i + 1));
    ++checked;
  }
  EXPECT_GT(checked, 200);
}

std::string plane_line(const testkit::Query& q) {
  std::string line;
  for (const Vec3* v : {&q.ray.origin, &q.ray.direction, &q.plane.point, &q.plane.normal})
    for (double c : {v->x, v->y, v->z}) {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, " %a", c);
      line += buffer;
    }
  return line;
}

// 3,000 queries of a triangle kind (under both rules) and of a plane kind: every rounding decided before GMP,
// and right.
void expect_kinds_never_reach_gmp(std::uint64_t seed, testkit::TriangleQueryKind triangle_kind,
                                  testkit::QueryKind plane_kind) {
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  for (int i = 0; i < 3000; ++i) {
    const testkit::TriangleQuery t = testkit::make_triangle_query(triangle_kind, bits);
    for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed})
      check_triangle(t.ray, t.triangle, rule, testkit::triangle_line(t));
    const testkit::Query p = testkit::make_query(plane_kind, bits);
    check_plane(p.ray, p.plane, plane_line(p));
  }
}

// The testkit's kinds built for the powers of two.
TEST(RoundingBoundary, AbovePowerOfTwoNeverReachesGmp) {
  expect_kinds_never_reach_gmp(20261129, testkit::TriangleQueryKind::above_power_of_two,
                               testkit::QueryKind::above_power_of_two);
}

// Rounding ties (and, for triangles, near ties: the origin nudged by a few ulps). Two things made this hold: the
// stage-3 candidate of a near tie can be t's neighbour, so the boundaries of both neighbours are tried
// (round_quotient_near); and at an exact tie the difference N·2 − (x + y)·D can come out of the expansion sum
// as same-signed adjacent components such as {−2^-64, −2^-63}, whose sign the checked rule top > 2·Σ lower
// cannot read but the one-sign rule can. Before them, 2.9% of these roundings reached GMP.
TEST(RoundingBoundary, RoundingTiesNeverReachGmp) {
  expect_kinds_never_reach_gmp(20261130, testkit::TriangleQueryKind::rounding_tie, testkit::QueryKind::rounding_tie);
}

// Near ties (t within 2^-20..2^-60 ulp of a midpoint): right, and almost always decided before GMP. Not always:
// the sign of N·2 − (x + y)·D at the boundary can come out of the expansion sum with a top component that is not
// twice the others and components of both signs ({2^-98, −2^-97}-like), which the checked sign leaves uncertain;
// 15 of 3,000 here (0.5%). Reading such signs (a renormalizing pass, or a tighter proved factor than 2) is open.
TEST(RoundingBoundary, NearTiesAreRightAndRarelyReachGmp) {
  testkit::SplitMix64 rng(20261131);
  const testkit::BitSource bits = [&rng] { return rng(); };
  int gmp = 0;
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const testkit::Query q = testkit::make_query(testkit::QueryKind::near_tie, bits);
    gmp += check_plane(q.ray, q.plane, plane_line(q), false);
  }
  RecordProperty("share_reaching_gmp", std::to_string(static_cast<double>(gmp) / n));
  EXPECT_LT(gmp, n / 100);
}

}  // namespace
}  // namespace raykernel
