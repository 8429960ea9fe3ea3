// Spheres in the nearest-hit module (docs/contract.md §10, "Scenes and nearest hits"): a sphere's hit is its
// smallest root t ≥ 0; among kinds the exact t decides, an exact tie goes to the plane, then the triangle, then
// the sphere, then the smaller index. Hand-derived cases (each expected answer worked out in the comment above
// it, in integers or in rationals computed here, never by the code under test), then a property: the certified
// scene query equals the exact reference (nearest_hit_exact with spheres) bit for bit, on scenes built to tie.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_scene.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include "surface_hits.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {
namespace {

using test::describe;
using test::same_answer;
using test::same_bits;

// The scene query on planes, a mesh and spheres, checked against the exact reference; returns the answer.
std::optional<SurfaceHit> nearest_checked(const Ray& ray, const std::vector<Plane>& planes, const Mesh* mesh,
                                          const std::vector<Sphere>& spheres) {
  const PlaneSet plane_set(planes);
  const SphereSet sphere_set(spheres);
  std::optional<PreparedMesh> prepared;
  if (mesh != nullptr) prepared.emplace(*mesh);
  const NearestScene scene{&plane_set, prepared ? &*prepared : nullptr, TriangleRule::owned, &sphere_set};
  const std::optional<SurfaceHit> hit = nearest_hit(ray, scene);
  const std::optional<SurfaceHit> exact = nearest_hit_exact(ray, planes, mesh, spheres);
  EXPECT_TRUE(same_answer(hit, exact)) << describe(hit) << " vs exact " << describe(exact);
  return hit;
}

const Ray along_x{{0, 0, 0}, {1, 0, 0}};

// Sphere (5, 0, 0) r 1 on the x axis: roots 4 and 6, the hit t = 4. The plane x = 4 meets the ray at t = 4 too:
// an exact tie, which the plane wins; a triangle in x = 4 around the axis also ties, and beats the sphere.
TEST(SphereNearest, ExactTiesGoToPlaneThenTriangleThenSphere) {
  const std::vector<Sphere> spheres{{{5, 0, 0}, 1}};
  const std::vector<Plane> plane{{{4, 0, 0}, {1, 0, 0}}};
  Mesh mesh;
  mesh.vertices = {{4, -1, -1}, {4, 3, -1}, {4, -1, 3}};
  mesh.triangles = {{0, 1, 2}};

  auto hit = nearest_checked(along_x, {}, nullptr, spheres);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->kind, SurfaceKind::sphere);
  EXPECT_EQ(hit->t, 4.0);
  hit = nearest_checked(along_x, plane, nullptr, spheres);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->kind, SurfaceKind::plane);
  hit = nearest_checked(along_x, {}, &mesh, spheres);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->kind, SurfaceKind::triangle);
  EXPECT_EQ(hit->t, 4.0);
}

// Two unit spheres touching at (4, 0, 0), centres (5, 0, 0) and (3, 0, 0). The ray x = 4, z = 0 from y = −5
// upwards is tangent to both at t = 5: an exact tie of two tangent roots, won by the smaller index. Along the
// x axis from 0 the sphere at 3 is first (t = 2), whatever its index.
TEST(SphereNearest, TouchingSpheres) {
  const std::vector<Sphere> spheres{{{5, 0, 0}, 1}, {{3, 0, 0}, 1}};
  const Ray up{{4, -5, 0}, {0, 1, 0}};
  auto hit = nearest_checked(up, {}, nullptr, spheres);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->kind, SurfaceKind::sphere);
  EXPECT_EQ(hit->index, 0u);
  EXPECT_EQ(hit->t, 5.0);
  hit = nearest_checked(up, {}, nullptr, {spheres[1], spheres[0]});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->index, 0u);
  hit = nearest_checked(along_x, {}, nullptr, spheres);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->index, 1u);
  EXPECT_EQ(hit->t, 2.0);
}

// Which root is the hit: from inside (origin at the centre of a sphere of radius 2) the far root t2 = 2; a sphere
// behind the ray (centre (−5, 0, 0)) is not hit; from a point of the surface, leaving outwards (origin (1, 0, 0)
// on the unit sphere at 0, direction +x: roots −2 and 0) the hit is t = 0, and entering (direction −x: roots 0
// and 2) also t = 0.
TEST(SphereNearest, TheSmallestRootAtOrBeyondTheOrigin) {
  auto hit = nearest_checked(along_x, {}, nullptr, {{{0, 0, 0}, 2}});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  EXPECT_FALSE(nearest_checked(along_x, {}, nullptr, {{{-5, 0, 0}, 1}}));
  for (const double dx : {1.0, -1.0}) {
    hit = nearest_checked(Ray{{1, 0, 0}, {dx, 0, 0}}, {}, nullptr, {{{0, 0, 0}, 1}});
    ASSERT_TRUE(hit);
    EXPECT_TRUE(same_bits(hit->t, 0.0));
  }
}

// A plane at x = RN(t1), t1 = 3 − √(5/4) the sphere's nearer root (centre (3, 1, 0), r = 3/2: A = 1, B = −3,
// C = 31/4, D = 5/4): both t round to the same double, so only the exact comparison can order them. Which is
// nearer is the sign of t1 − RN(t1), i.e. of (3 − RN(t1))² − 5/4 (3 − RN(t1) > 0), computed here in rationals.
// Moved by one ulp either way, the plane is ordered by the roundings alone.
TEST(SphereNearest, APlaneWithinHalfAnUlpOfARoot) {
  const std::vector<Sphere> spheres{{{3, 1, 0}, 1.5}};
  const SphereIntersection s = intersect(along_x, spheres[0]);
  ASSERT_EQ(s.relation, SphereRelation::cross);
  const mpq_class r(s.t1), gap = (3 - r) * (3 - r) - mpq_class(5, 4);
  ASSERT_NE(sgn(gap), 0);  // t1 is irrational
  const bool sphere_nearer = sgn(gap) < 0;  // t1 < RN(t1) ⟺ √(5/4) > 3 − RN(t1) ⟺ (3 − RN(t1))² < 5/4
  for (const double x : {s.t1, std::nextafter(s.t1, 0.0), std::nextafter(s.t1, 4.0)}) {
    const auto hit = nearest_checked(along_x, {{{x, 0, 0}, {1, 0, 0}}}, nullptr, spheres);
    ASSERT_TRUE(hit);
    if (x < s.t1) {
      EXPECT_EQ(hit->kind, SurfaceKind::plane);
    } else if (x > s.t1) {
      EXPECT_EQ(hit->kind, SurfaceKind::sphere);
    } else {
      EXPECT_EQ(hit->kind, sphere_nearer ? SurfaceKind::sphere : SurfaceKind::plane);
    }
  }
}

// An invalid sphere is named with its index; an empty sphere set changes nothing.
TEST(SphereNearest, InvalidSpheresAreNamed) {
  const std::vector<Sphere> spheres{{{0, 0, 0}, 1}, {{0, 0, 0}, -0.0}};
  try {
    const SphereSet set(spheres);
    ADD_FAILURE() << "no error";
  } catch (const invalid_input& e) {
    EXPECT_EQ(std::string(e.what()), "sphere 1: sphere radius is not positive");
  }
  const SphereSet none(std::vector<Sphere>{});
  EXPECT_FALSE(nearest_hit(along_x, NearestScene{nullptr, nullptr, TriangleRule::owned, &none}));
  EXPECT_EQ(validate(Sphere{{0, NAN, 0}, 1}), std::optional<std::string>("sphere center y is NaN"));
}

// Scenes built to tie: spheres through a common point of the ray (the same hit point on several spheres of
// different radii and centres along the normal), planes through RN of a sphere's root and one ulp off, a small
// sphere tangent to the ray, all in random order; the certified answer is the reference's bit for bit.
RC_GTEST_PROP(SphereNearest, CertifiedEqualsExactOnTiedScenes, ()) {
  const int ox = *rc::gen::inRange(-8, 8), oy = *rc::gen::inRange(-8, 8), oz = *rc::gen::inRange(-8, 8);
  const int dx = *rc::gen::inRange(-4, 5), dy = *rc::gen::inRange(-4, 5), dz = *rc::gen::inRange(1, 5);
  const Ray ray{{double(ox), double(oy), double(oz)}, {double(dx), double(dy), double(dz)}};
  std::vector<Sphere> spheres;
  const int n = *rc::gen::inRange(1, 20);  // from SphereSet::bvh_min_spheres on, the set walks its hierarchy
  for (int k = 0; k < n; ++k) {
    // A point of the ray at t = s/4 and a centre beyond it along an integer normal: the sphere through that point.
    const int s = *rc::gen::inRange(0, 40);
    const double px = ox + dx * (s / 4.0), py = oy + dy * (s / 4.0), pz = oz + dz * (s / 4.0);
    const int nx = *rc::gen::inRange(-3, 4), ny = *rc::gen::inRange(-3, 4), nz = *rc::gen::inRange(-3, 4);
    const int scale = *rc::gen::inRange(1, 4);
    const Vec3 c{px + nx * scale, py + ny * scale, pz + nz * scale};
    const double r2 = double(nx * nx + ny * ny + nz * nz) * scale * scale;
    if (r2 == 0) continue;
    const bool perturb = *rc::gen::arbitrary<bool>();
    double r = std::sqrt(r2);  // RN(√r2): exact for perfect squares, else an ulp from the exact point
    if (perturb) r = std::nextafter(r, *rc::gen::arbitrary<bool>() ? 0.0 : 1e9);
    spheres.push_back({c, r});
  }
  if (spheres.empty()) spheres.push_back({{double(ox + 3), double(oy), double(oz + 3)}, 1.5});
  std::vector<Plane> planes;
  // A plane through RN of a sphere's hit, perpendicular to an axis, and one a few ulps off.
  const SphereIntersection first = intersect(ray, spheres[*rc::gen::inRange<std::size_t>(0, spheres.size())]);
  if (first.relation != SphereRelation::miss && first.t1 >= 0) {
    const Vec3 p{ray.origin.x + first.t1 * ray.direction.x, ray.origin.y + first.t1 * ray.direction.y,
                 ray.origin.z + first.t1 * ray.direction.z};
    planes.push_back({p, {0, 0, 1}});
    const int ulps = *rc::gen::inRange(-2, 3);
    double z = p.z;
    for (int i = 0; i < std::abs(ulps); ++i) z = std::nextafter(z, ulps < 0 ? -1e9 : 1e9);
    planes.push_back({{p.x, p.y, z}, {double(dx), double(dy), double(dz)}});
  }
  const PlaneSet plane_set(planes);
  const SphereSet sphere_set(spheres);
  const NearestScene scene{&plane_set, nullptr, TriangleRule::owned, &sphere_set};
  const TracedSceneHit traced = nearest_hit_traced(ray, scene);
  const std::optional<SurfaceHit> exact = nearest_hit_exact(ray, planes, nullptr, spheres);
  RC_TAG(traced.comparison_stage == Stage::exact ? "a tie of roundings, ordered in rationals" : "ordered by roundings");
  RC_ASSERT(same_answer(traced.hit, exact));
  RC_ASSERT(same_answer(nearest_hit(ray, scene), exact));
}

// ---- intervals (docs/contract.md §8 and §10) ------------------------------------------------------------------

double below(double x) { return std::nextafter(x, -INFINITY); }
double above(double x) { return std::nextafter(x, INFINITY); }

std::optional<SphereHit> in_interval_checked(const Ray& ray, const RayInterval& interval, const std::vector<Sphere>& spheres) {
  const SphereSet set(spheres);
  const std::optional<SphereHit> hit = nearest_hit(ray, interval, set);
  const std::optional<SphereHit> exact = nearest_hit_exact(ray, interval, spheres);
  EXPECT_EQ(hit.has_value(), exact.has_value());
  if (hit && exact) {
    EXPECT_EQ(hit->sphere, exact->sphere);
    EXPECT_TRUE(same_bits(hit->t, exact->t));
  }
  EXPECT_EQ(occluded(ray, interval, set), exact.has_value());
  return hit;
}

// Sphere (5, 0, 0) r 1 along the x axis: roots 4 and 6. The interval is closed: [0, 4] holds 4, [0, 4⁻] nothing,
// [4.5, 10] the far root 6, [6, 6] 6, [6⁺, inf] nothing. The ray x = 4 from y = −5 is tangent at t = 5: [5, 5]
// holds it, [5⁺, 9] not.
TEST(SphereInterval, ClosedBoundsHandDerived) {
  const std::vector<Sphere> s{{{5, 0, 0}, 1}};
  struct Case {
    RayInterval interval;
    std::optional<double> t;
  };
  for (const Case& c : {Case{{0, 4}, 4.0}, Case{{0, below(4)}, std::nullopt}, Case{{4.5, 10}, 6.0}, Case{{6, 6}, 6.0},
                        Case{{above(6), INFINITY}, std::nullopt}, Case{{0, INFINITY}, 4.0}}) {
    const auto hit = in_interval_checked(along_x, c.interval, s);
    EXPECT_EQ(hit.has_value(), c.t.has_value()) << c.interval.t_min << " " << c.interval.t_max;
    if (hit && c.t) EXPECT_EQ(hit->t, *c.t);
    const auto root = nearest_root(along_x, c.interval, s[0]);
    EXPECT_EQ(root.has_value(), c.t.has_value());
  }
  const Ray up{{4, -5, 0}, {0, 1, 0}};
  EXPECT_TRUE(in_interval_checked(up, {5, 5}, s));
  EXPECT_FALSE(in_interval_checked(up, {above(5), 9}, s));
  EXPECT_FALSE(in_interval_checked(up, {0, below(5)}, s));
}

// A bound equal to RN of an irrational root (centre (3, 1, 0), r 3/2: t1 = 3 − √(5/4)): whether [RN(t1), inf]
// holds t1 is the sign of t1 − RN(t1), decided from (3 − RN(t1))² − 5/4 in rationals here; [0, RN(t1)] holds it
// exactly when the other does not (t1 ≠ RN(t1)), then the far root t2 = 3 + √(5/4) is the hit of [RN(t1), inf]
// when t1 is below it.
TEST(SphereInterval, ABoundWithinHalfAnUlpOfAnIrrationalRoot) {
  const std::vector<Sphere> s{{{3, 1, 0}, 1.5}};
  const SphereIntersection r = intersect(along_x, s[0]);
  const mpq_class b(r.t1), gap = (3 - b) * (3 - b) - mpq_class(5, 4);
  ASSERT_NE(sgn(gap), 0);
  const bool root_above_bound = sgn(gap) > 0;  // t1 > RN(t1) ⟺ √(5/4) < 3 − RN(t1) ⟺ (3 − RN(t1))² > 5/4
  const auto from = in_interval_checked(along_x, {r.t1, INFINITY}, s);
  ASSERT_TRUE(from);
  EXPECT_EQ(from->t, root_above_bound ? r.t1 : r.t2);
  EXPECT_EQ(in_interval_checked(along_x, {0, r.t1}, s).has_value(), !root_above_bound);
  EXPECT_THROW((void)nearest_root(along_x, {2, 1}, s[0]), invalid_input);
}

// Random rays and spheres of the testkit's hard kinds' spirit — roots on doubles, tangents, the origin on the
// surface — with interval bounds at a root's rounding and an ulp either side: the certified answer is the
// reference's bit for bit.
RC_GTEST_PROP(SphereInterval, CertifiedEqualsExactAtTheBounds, ()) {
  const Ray ray{{double(*rc::gen::inRange(-6, 6)), double(*rc::gen::inRange(-6, 6)), 0.5 * *rc::gen::inRange(-6, 6)},
                {double(*rc::gen::inRange(-3, 4)), double(*rc::gen::inRange(-3, 4)), double(*rc::gen::inRange(1, 4))}};
  std::vector<Sphere> spheres;
  const int n = *rc::gen::inRange(1, 16);  // from SphereSet::bvh_min_spheres on, the set walks its hierarchy
  for (int k = 0; k < n; ++k) {
    // Near the ray: o + s·d plus a small offset of quarter units (the ray's line meets most of them).
    const double along = 0.5 * *rc::gen::inRange(-2, 12);
    const Vec3 c{ray.origin.x + along * ray.direction.x + 0.25 * *rc::gen::inRange(-4, 5),
                 ray.origin.y + along * ray.direction.y + 0.25 * *rc::gen::inRange(-4, 5),
                 ray.origin.z + along * ray.direction.z + 0.25 * *rc::gen::inRange(-4, 5)};
    const double r = *rc::gen::element(0.5, 1.0, 1.5, 2.0, std::sqrt(2.0), std::sqrt(3.0), 0.3);
    spheres.push_back({c, r});
  }
  const SphereIntersection first = intersect(ray, spheres[0]);
  std::vector<double> bounds{0.0, 0.5, 3.0};
  if (first.relation != SphereRelation::miss)
    for (const double t : {first.t1, first.t2})
      if (t >= 0 && std::isfinite(t))
        for (const double b : {t, below(t), above(t)})
          if (!std::signbit(b)) bounds.push_back(b);  // an interval starts at 0 or beyond
  const double lo = *rc::gen::elementOf(bounds);
  const double hi = *rc::gen::elementOf(bounds);
  const RayInterval interval{std::min(lo, hi), *rc::gen::arbitrary<bool>() ? INFINITY : std::max(lo, hi)};
  const SphereSet set(spheres);
  const std::optional<SphereHit> hit = nearest_hit(ray, interval, set);
  const std::optional<SphereHit> exact = nearest_hit_exact(ray, interval, spheres);
  RC_TAG(exact ? "hit" : "no hit");
  RC_ASSERT(hit.has_value() == exact.has_value());
  if (hit) {
    RC_ASSERT(hit->sphere == exact->sphere);
    RC_ASSERT(same_bits(hit->t, exact->t));
  }
  RC_ASSERT(occluded(ray, interval, set) == exact.has_value());
}

// A set large enough for its hierarchy (SphereSet::bvh): a cover in the spirit of Ray Tracing in One Weekend —
// 300 small spheres resting on a huge one, some touching each other, some placed so rays tie between them —
// against the exact reference for rays from above and grazing ones, with and without an interval, and occluded.
TEST(SphereNearest, ALargeSetWalksItsHierarchyAndAgreesWithExact) {
  testkit::SplitMix64 rng(31);
  const auto uniform = [&rng](double lo, double hi) { return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1p-53; };
  std::vector<Sphere> spheres{{{0, -1000, 0}, 1000}};
  for (int k = 0; k < 300; ++k) {
    const double r = k % 3 == 0 ? 0.5 : 0.25 * (1 + static_cast<int>(rng() % 3));
    const double x = std::round(uniform(-20, 20) * 4) / 4, z = std::round(uniform(-20, 20) * 4) / 4;
    spheres.push_back({{x, r, z}, r});  // touching the ground plane y = 0 (the huge sphere is just below it)
    if (k % 10 == 0) spheres.push_back({{x + 2 * r, r, z}, r});  // touching its neighbour at x + r
  }
  const SphereSet set(spheres);
  ASSERT_NE(set.bvh(), nullptr);
  int hits = 0;
  for (int i = 0; i < 600; ++i) {
    const Vec3 o{uniform(-25, 25), i % 2 == 0 ? uniform(0.1, 6) : 10.0, uniform(-25, 25)};
    const Vec3 d{uniform(-1, 1), i % 2 == 0 ? uniform(-0.2, 0.05) : -1.0, uniform(-1, 1)};
    const Ray ray{o, d};
    for (const RayInterval interval : {RayInterval{}, RayInterval{0.5, 12.0}}) {
      const std::optional<SphereHit> hit = nearest_hit(ray, interval, set);
      const std::optional<SphereHit> exact = nearest_hit_exact(ray, interval, spheres);
      ASSERT_EQ(hit.has_value(), exact.has_value()) << i;
      if (hit) {
        ++hits;
        EXPECT_EQ(hit->sphere, exact->sphere) << i;
        EXPECT_TRUE(same_bits(hit->t, exact->t)) << i;
      }
      EXPECT_EQ(occluded(ray, interval, set), exact.has_value()) << i;
    }
  }
  EXPECT_GT(hits, 600);
}

}  // namespace
}  // namespace raykernel
