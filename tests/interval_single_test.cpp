// docs/contract.md §8 on one primitive: intersect(ray, interval, plane) and intersect(ray, interval, triangle,
// options) — the hit only when its exact t lies in [t_min, t_max] — checked on hand-derived cases (t exactly on a
// bound and an ulp beside it, t = 1/3 whose rounding lies below it, invalid bounds named) and, by RapidCheck, the
// certified path against the exact references (intersect_exact with the interval) on the testkit's hard queries of
// every kind with bounds at and beside each rounded t.
#include "invalid_reason.hpp"

#include <raykernel/plane.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
double up(double x) { return std::nextafter(x, inf); }
double down(double x) { return std::nextafter(x, -inf); }
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

const Plane z_is_1{{0, 0, 1}, {0, 0, 1}};
const Triangle in_z_is_1{{-1, -1, 1}, {2, -1, 1}, {-1, 2, 1}};  // contains (0, 0, 1)

TEST(IntervalOnOnePrimitive, ABoundExactlyOnTIsInside) {
  // The ray from the origin along (0, 0, 2) meets z = 1 at t = 1/2 exactly (a double).
  const Ray ray{{0, 0, 0}, {0, 0, 2}};
  for (const RayInterval i : {RayInterval{0.5, 0.5}, RayInterval{0, 0.5}, RayInterval{0.5, inf}, RayInterval{down(0.5), up(0.5)}}) {
    ASSERT_TRUE(intersect(ray, i, z_is_1).has_value());
    EXPECT_EQ(intersect(ray, i, z_is_1)->t, 0.5);
    ASSERT_TRUE(intersect(ray, i, in_z_is_1).has_value());
    EXPECT_EQ(intersect(ray, i, in_z_is_1)->t, 0.5);
  }
  for (const RayInterval i : {RayInterval{up(0.5), inf}, RayInterval{0, down(0.5)}, RayInterval{0.75, 1}}) {
    EXPECT_FALSE(intersect(ray, i, z_is_1).has_value());
    EXPECT_FALSE(intersect(ray, i, in_z_is_1).has_value());
    EXPECT_FALSE(intersect_exact(ray, i, z_is_1).has_value());
    EXPECT_FALSE(intersect_exact(ray, i, in_z_is_1).has_value());
  }
}

TEST(IntervalOnOnePrimitive, TheExactTIsComparedNotItsRounding) {
  // Along (0, 0, 3): t = 1/3, whose rounding r = RN(1/3) lies below it. So t_min = r lets it through and
  // t_max = r does not, although the rounded t equals both.
  const Ray ray{{0, 0, 0}, {0, 0, 3}};
  const double r = 1.0 / 3;
  ASSERT_LT(r * 3, 1.0 + 0x1p-52);  // (r is below 1/3: 3r = 1 − 2^-54 exactly, rounded to 1 here)
  EXPECT_TRUE(intersect(ray, {r, inf}, z_is_1).has_value());
  EXPECT_FALSE(intersect(ray, {0, r}, z_is_1).has_value());
  EXPECT_TRUE(intersect(ray, {0, up(r)}, z_is_1).has_value());
  EXPECT_FALSE(intersect(ray, {up(r), inf}, z_is_1).has_value());
  EXPECT_TRUE(intersect(ray, {r, inf}, in_z_is_1).has_value());
  EXPECT_FALSE(intersect(ray, {0, r}, in_z_is_1).has_value());
  EXPECT_TRUE(intersect(ray, {0, up(r)}, in_z_is_1).has_value());
  EXPECT_FALSE(intersect(ray, {up(r), inf}, in_z_is_1).has_value());
  EXPECT_EQ(intersect(ray, {r, up(r)}, in_z_is_1)->t, r);
}

TEST(IntervalOnOnePrimitive, AnOriginOnTheSurfaceIsInsideAClosedIntervalFromZero) {
  const Ray ray{{0, 0, 1}, {0, 0, 1}};  // t = 0
  EXPECT_TRUE(intersect(ray, {0, 0}, z_is_1).has_value());
  EXPECT_TRUE(intersect(ray, {0, inf}, in_z_is_1).has_value());
  EXPECT_FALSE(intersect(ray, {0x1p-1074, inf}, in_z_is_1).has_value());
  // Behind, and a miss beside the triangle, are never inside an interval.
  EXPECT_FALSE(intersect(Ray{{0, 0, 2}, {0, 0, 1}}, {0, inf}, z_is_1).has_value());
  EXPECT_FALSE(intersect(Ray{{5, 5, 0}, {0, 0, 1}}, {0, inf}, in_z_is_1).has_value());
}

TEST(IntervalOnOnePrimitive, InvalidBoundsAreNamed) {
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  using test::invalid_reason;
  EXPECT_NE(invalid_reason([&] { (void)intersect(ray, {std::nan(""), 1}, z_is_1); }).find("t_min is NaN"), std::string::npos);
  EXPECT_NE(invalid_reason([&] { (void)intersect(ray, {2, 1}, in_z_is_1); }).find("t_min is greater than t_max"),
            std::string::npos);
  EXPECT_NE(invalid_reason([&] { (void)intersect(ray, {-1, 1}, in_z_is_1); }).find("t_min is negative"), std::string::npos);
  EXPECT_NE(invalid_reason([&] { (void)intersect(Ray{{0, 0, 0}, {0, 0, 0}}, {0, 1}, z_is_1); }).find("zero"),
            std::string::npos);
}

// Bounds at and beside the rounded t of a query, and 0 and +inf; two of them, ordered.
RayInterval interval_around(double t) {
  std::vector<double> b{0.0, inf};
  if (std::isfinite(t) && t >= 0) b.insert(b.end(), {t, down(t) < 0 ? 0.0 : down(t), up(t)});
  const double x = b[*rc::gen::inRange<std::size_t>(0, b.size())], y = b[*rc::gen::inRange<std::size_t>(0, b.size())];
  double lo = std::min(x, y), hi = std::max(x, y);
  if (std::isinf(lo)) lo = 0;
  return {lo, hi};
}

testkit::BitSource rc_bits() {
  return [] { return *rc::gen::inRange<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max()); };
}

RC_GTEST_PROP(IntervalOnOnePrimitive, PlaneCertifiedEqualsExact, ()) {
  const auto kind = *rc::gen::elementOf(testkit::all_query_kinds);
  const testkit::Query q = testkit::make_query(kind, rc_bits());
  RC_PRE(!validate(q.ray, q.plane).has_value());
  const RayInterval interval = interval_around(intersect_exact(q.ray, q.plane).t);
  const std::optional<Intersection> got = intersect(q.ray, interval, q.plane);
  const std::optional<Intersection> want = intersect_exact(q.ray, interval, q.plane);
  RC_TAG(testkit::to_string(kind), want ? "inside" : "outside");
  RC_ASSERT(got.has_value() == want.has_value());
  if (want) RC_ASSERT(same_bits(got->t, want->t));
}

RC_GTEST_PROP(IntervalOnOnePrimitive, TriangleCertifiedEqualsExact, ()) {
  const auto kind = *rc::gen::elementOf(testkit::all_triangle_query_kinds);
  const testkit::TriangleQuery q = testkit::make_triangle_query(kind, rc_bits());
  RC_PRE(!validate(q.ray, q.triangle).has_value());
  const TriangleOptions options{*rc::gen::arbitrary<bool>() ? TriangleRule::owned : TriangleRule::closed, true, true};
  const RayInterval interval = interval_around(intersect_exact(q.ray, q.triangle, options).t);
  const std::optional<TriangleIntersection> got = intersect(q.ray, interval, q.triangle, options);
  const std::optional<TriangleIntersection> want = intersect_exact(q.ray, interval, q.triangle, options);
  RC_TAG(testkit::to_string(kind), want ? "inside" : "outside");
  RC_ASSERT(got.has_value() == want.has_value());
  if (!want) return;
  RC_ASSERT(got->location == want->location);
  RC_ASSERT(same_bits(got->t, want->t));
  RC_ASSERT(same_bits(got->barycentric.a, want->barycentric.a));
  RC_ASSERT(same_bits(got->barycentric.b, want->barycentric.b));
  RC_ASSERT(same_bits(got->barycentric.c, want->barycentric.c));
}

}  // namespace
}  // namespace raykernel
