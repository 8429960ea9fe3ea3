// The exact ground truth of secondary rays (<raykernel/spawn.hpp>: hits_exact, first_hits_exact, plane_side,
// direction_side, rounded_hit_point) and the published offset methods of baselines/offsets, on hand-derived
// cases; first_hits_exact against the certified nearest hit (closed rule, its own BVH and cascade) by
// RapidCheck.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/spawn.hpp>

#include "offset_methods.hpp"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace raykernel {
namespace {

const Triangle floor_triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // z = 0, N = (0, 0, 1)

double up(double x) { return std::nextafter(x, std::numeric_limits<double>::infinity()); }
double down(double x) { return std::nextafter(x, -std::numeric_limits<double>::infinity()); }

TEST(SecondaryExact, TheIntervalIsComparedExactly) {
  // From (0.25, 0.25, 1) straight down: the floor at t = 1 exactly.
  const HitPoint from = HitPoint::at({0.25, 0.25, 1});
  const Vec3 w{0, 0, -1};
  EXPECT_TRUE(hits_exact(from, floor_triangle, w, floor_triangle, {1, true}));
  EXPECT_FALSE(hits_exact(from, floor_triangle, w, floor_triangle, {1, false}));
  EXPECT_FALSE(hits_exact(from, floor_triangle, w, floor_triangle, {up(1), true}));
  EXPECT_TRUE(hits_exact(from, floor_triangle, w, floor_triangle, {down(1), false}));
  // Upwards the floor is behind; along it (w·N = 0) it is coplanar-parallel and never counts.
  EXPECT_FALSE(hits_exact(from, floor_triangle, {0, 0, 1}, floor_triangle));
  EXPECT_FALSE(hits_exact(HitPoint::at({0.25, 0.25, 0}), floor_triangle, {1, 0, 0}, floor_triangle));
  // The closed triangle: its vertex (1, 0, 0) and a point of its edge x + y = 1 count, a point beyond does not.
  EXPECT_TRUE(hits_exact(HitPoint::at({1, 0, 1}), floor_triangle, w, floor_triangle));
  EXPECT_TRUE(hits_exact(HitPoint::at({0.5, 0.5, 1}), floor_triangle, w, floor_triangle));
  EXPECT_FALSE(hits_exact(HitPoint::at({0.5, up(0.5), 1}), floor_triangle, w, floor_triangle));
}

TEST(SecondaryExact, FromTheExactHitPointOfACrossing) {
  // The ray from (0, 0, 1) along (1, 0, -3) crosses the floor's plane at P = (1/3, 0, 0), not a double.
  // RN(1/3) = 0x1.5555555555555p-2 is below 1/3 (the first bit rounded off is 0), so a wall at x = RN(1/3)
  // is behind P along +x and ahead of it along −x — and the ray from RN(P) itself touches it at t = 0.
  const double third = 0x1.5555555555555p-2;
  ASSERT_EQ(1.0 / 3, third);
  const Triangle wall{{third, -1, -1}, {third, 1, -1}, {third, 0, 1}};
  const Mesh mesh{{floor_triangle.a, floor_triangle.b, floor_triangle.c, wall.a, wall.b, wall.c}, {{0, 1, 2}, {3, 4, 5}}};
  const HitPoint p = HitPoint::crossing({{0, 0, 1}, {1, 0, -3}});
  EXPECT_EQ(rounded_hit_point(p, floor_triangle).x, third);
  EXPECT_TRUE(first_hits_exact(p, floor_triangle, {1, 0, 0}, mesh, {0, false}, 0u).empty());
  EXPECT_EQ(first_hits_exact(p, floor_triangle, {-1, 0, 0}, mesh, {0, false}, 0u), std::vector<std::uint32_t>{1});
  EXPECT_EQ(first_hits_exact(HitPoint::at({third, 0, 0}), floor_triangle, {1, 0, 0}, mesh, {0, true}, 0u),
            std::vector<std::uint32_t>{1});
  // Leaving the floor at P downwards: the floor itself at t = 0 (skipped, or left out by t > 0), then nothing.
  EXPECT_TRUE(first_hits_exact(p, floor_triangle, {0, 0, -1}, mesh, {0, false}).empty());
  EXPECT_EQ(first_hits_exact(p, floor_triangle, {0, 0, -1}, mesh, {0, true}), std::vector<std::uint32_t>{0});
}

TEST(SecondaryExact, TiesAreAllReturnedInIndexOrder) {
  // Two copies of the floor and one below it: a ray down through both copies at the same t.
  const Mesh mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {{3, 4, 5}, {0, 1, 2}, {2, 0, 1}}};
  EXPECT_EQ(first_hits_exact(HitPoint::at({0.25, 0.25, 1}), floor_triangle, {0, 0, -1}, mesh),
            (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(first_hits_exact(HitPoint::at({0.25, 0.25, 1}), floor_triangle, {0, 0, -1}, mesh, {}, 1u),
            std::vector<std::uint32_t>{2});
}

TEST(SecondaryExact, SidesAndInvalidInput) {
  EXPECT_EQ(plane_side({0, 0, 0x1p-1074}, floor_triangle), 1);
  EXPECT_EQ(plane_side({5, -7, 0}, floor_triangle), 0);
  EXPECT_EQ(plane_side({0, 0, -0x1p-1074}, floor_triangle), -1);
  EXPECT_EQ(direction_side({1, 1, -0x1p-1074}, floor_triangle), -1);
  EXPECT_EQ(direction_side({1, 1, 0}, floor_triangle), 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Mesh mesh{{floor_triangle.a, floor_triangle.b, floor_triangle.c}, {{0, 1, 2}}};
  EXPECT_THROW((void)first_hits_exact(HitPoint::at({0, 0, 1}), floor_triangle, {0, 0, 0}, mesh), invalid_input);
  EXPECT_THROW((void)first_hits_exact(HitPoint::at({0, nan, 1}), floor_triangle, {0, 0, 1}, mesh), invalid_input);
  EXPECT_THROW((void)first_hits_exact(HitPoint::at({0, 0, 1}), floor_triangle, {0, 0, 1}, mesh, {-1, true}), invalid_input);
  EXPECT_THROW((void)hits_exact(HitPoint::crossing({{0, 0, 1}, {1, 0, 0}}), floor_triangle, {0, 0, 1}, floor_triangle),
               invalid_input);  // the crossing ray is parallel to the floor
  EXPECT_THROW((void)plane_side({0, 0, nan}, floor_triangle), invalid_input);
}

// The box test never sets aside the first hit: from a point of doubles with t ≥ 0, the first triangles are those
// the certified nearest hit (closed rule, ties to the smallest index) finds through its BVH.
RC_GTEST_PROP(SecondaryExact, FirstHitsAgreeWithTheNearestHit, ()) {
  const auto coordinate = rc::gen::map(rc::gen::inRange(-8, 9), [](int k) { return k / 4.0; });
  const auto point = rc::gen::apply([](double x, double y, double z) { return Vec3{x, y, z}; }, coordinate, coordinate, coordinate);
  const std::vector<Vec3> vertices = *rc::gen::container<std::vector<Vec3>>(9, point);
  Mesh mesh{vertices, {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {0, 4, 8}, {2, 3, 7}}};
  const Vec3 o = *point, w = *point;
  RC_PRE(!(w.x == 0 && w.y == 0 && w.z == 0));
  const std::vector<std::uint32_t> first = first_hits_exact(HitPoint::at(o), floor_triangle, w, mesh, {0, true});
  const std::optional<MeshHit> nearest = nearest_hit(Ray{o, w}, mesh, TriangleRule::closed);
  RC_ASSERT(first.empty() == !nearest.has_value());
  if (nearest) RC_ASSERT(first.front() == nearest->triangle);
}

// ---- The offset methods, by hand ----------------------------------------------------------------------------

baseline::OffsetHit floor_hit(const Vec3& p, const Vec3& w) {
  baseline::OffsetHit h{};
  h.p64 = h.p32 = p;
  h.triangle = floor_triangle;
  h.barycentric = {1 - p.x - p.y, p.x, p.y};
  h.primary_origin = {p.x, p.y, 1};
  h.primary_t = 1;
  h.direction = w;
  return h;
}

TEST(OffsetMethods, RayTracingGemsMovesBitsOrAddsNearZero) {
  // Near zero (|z| < 1/32) float_scale·Ng = 2^-16 is added; x = 0.25 ≥ 1/32 moves by int(256·0) = 0 ulps.
  const baseline::OffsetRay up_ray = baseline::offset_ray(baseline::OffsetMethod::ray_tracing_gems, floor_hit({0.25, 0.25, 0}, {0, 0, 1}));
  EXPECT_EQ(up_ray.origin.x, 0.25);
  EXPECT_EQ(up_ray.origin.z, 0x1p-16);
  const baseline::OffsetRay down_ray = baseline::offset_ray(baseline::OffsetMethod::ray_tracing_gems, floor_hit({0.25, 0.25, 0}, {0, 0, -1}));
  EXPECT_EQ(down_ray.origin.z, -0x1p-16);
  // A wall x = 2 with its normal along +x: 2's bits move by 256 (2 + 256·2^-22).
  baseline::OffsetHit wall = floor_hit({2, 0.25, 0.25}, {1, 0, 0});
  wall.triangle = {{2, 0, 0}, {2, 1, 0}, {2, 0, 1}};
  EXPECT_EQ(baseline::offset_ray(baseline::OffsetMethod::ray_tracing_gems, wall).origin.x, 2 + 0x1p-14);
}

TEST(OffsetMethods, Mitsuba3AndEmbreeAndOneWeekend) {
  // Mitsuba 3: (1 + max|p|)·1500·2^-24 along n; at p = (1, 0.25, 0.25) on the wall x = 1: 2·1500·2^-24 = 1500·2^-23,
  // a multiple of the float spacing at 1.
  baseline::OffsetHit wall = floor_hit({1, 0.25, 0.25}, {1, 0, 0});
  wall.triangle = {{1, 0, 0}, {1, 1, 0}, {1, 0, 1}};
  EXPECT_EQ(baseline::offset_ray(baseline::OffsetMethod::mitsuba3, wall).origin.x, 1 + 1500 * 0x1p-23);
  // Embree's tutorial: e = (1, 1, 1) (the vertices and the origin (0.25, 0.25, 1)), tfar = 1: eps = 32·float(1.19209e-07),
  // a power-of-two multiple; the origin moves by eps along +z, and tnear = eps.
  const baseline::OffsetRay e = baseline::offset_ray(baseline::OffsetMethod::embree_tutorial, floor_hit({0.25, 0.25, 0}, {0, 0, 1}));
  const double eps = std::ldexp(static_cast<double>(1.19209e-07f), 5);
  EXPECT_EQ(e.origin.z, eps);
  EXPECT_EQ(e.t_min, eps);
  EXPECT_TRUE(e.t_min_included);
  // Ray Tracing in One Weekend: the hit point itself, and t > 0.001.
  const baseline::OffsetRay o = baseline::offset_ray(baseline::OffsetMethod::one_weekend, floor_hit({0.25, 0.25, 0}, {0, 0, 1}));
  EXPECT_EQ(o.origin.z, 0);
  EXPECT_EQ(o.t_min, 0.001);
  EXPECT_FALSE(o.t_min_included);
}

TEST(OffsetMethods, PbrtErrorBoundIsZeroOnAnAxisWhereEveryVertexIsZero) {
  // p_i all have z = 0, so pError.z = gamma(7)·0 = 0; n = (0, 0, ±1) makes d = |n|·pError = 0: no offset, and no
  // rounding away (offset components are 0). The origin is P itself, on the plane.
  const baseline::OffsetRay r = baseline::offset_ray(baseline::OffsetMethod::pbrt_v4, floor_hit({0.25, 0.25, 0}, {0, 0, 1}));
  EXPECT_EQ(r.origin.x, 0.25);
  EXPECT_EQ(r.origin.y, 0.25);
  EXPECT_EQ(r.origin.z, 0);
  EXPECT_FALSE(r.t_min_included);
  // Off the axes pError > 0: on the wall x = 1 at (1, 0.25, 0.25), pError.x = gamma(7)·(b0 + b1 + b2)·1 > 0 moves x
  // up by at least one float ulp (the NextFloatUp after the offset).
  baseline::OffsetHit wall = floor_hit({1, 0.25, 0.25}, {1, 0, 0});
  wall.triangle = {{1, 0, 0}, {1, 1, 0}, {1, 0, 1}};
  wall.barycentric = {0.5, 0.25, 0.25};
  EXPECT_GE(baseline::offset_ray(baseline::OffsetMethod::pbrt_v4, wall).origin.x, 1 + 0x1p-23);
}

}  // namespace
}  // namespace raykernel
