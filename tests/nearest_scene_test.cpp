// The nearest-hit module over several kinds of surface (kernel/include/raykernel/nearest_scene.hpp,
// kernel/src/nearest/): nearest_hit(ray, NearestScene) of planes and a mesh against nearest_hit_exact, the brute
// force in exact rationals (every plane's and triangle's t, the smallest exactly, a plane before a triangle on an
// exact tie, then the smaller index): the same kind, index and t bit for bit (and barycentric coordinates when
// asked), or both no hit.
//
// - Mixed scenes (RapidCheck): a closed test mesh, a random soup or a tie soup, with planes made to meet the ray
//   where it meets the mesh — through the very point it is aimed at (a vertex, an edge point shared by two
//   triangles, a point inside a face: exact ties between kinds), through that point moved by 2^-60 of the scale
//   (near ties), along a coordinate plane of an axis-aligned mesh face — and random planes; rays aimed at
//   vertices, edge points, face points and the bounding box, under both rules. The traced query answers the same.
// - The scene query equals the planes' and the mesh's own queries combined by exact comparison (one module).
// - Hand-derived: a plane holding a facet ties with it and wins; moved by 2^-20 behind it, the facet wins; a
//   triangle before a plane by less than an ulp.
// - Rounding ties of a triangle's t (t exactly halfway between two doubles), decided at the rounding boundaries in
//   expansions (core/quotient_boundary.hpp), never in rationals: the octahedron scene's rays, and
//   round_quotient_at_boundaries itself against exact rounding on random quotients near and on midpoints.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/nearest_scene.hpp>
#include <raykernel/testkit/mesh_rapidcheck.hpp>
#include <raykernel/testkit/meshes.hpp>

#include "surface_hits.hpp"

#include "core/expansion.hpp"
#include "core/quotient_boundary.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {
namespace {

constexpr int kBatch = 20;  // rays per property case

using test::describe;
using test::same_answer;
using test::same_bits;

std::string describe(const Ray& r) {
  char s[256];
  std::snprintf(s, sizeof s, "ray (%a %a %a) + t(%a %a %a)", r.origin.x, r.origin.y, r.origin.z, r.direction.x,
                r.direction.y, r.direction.z);
  return s;
}

double scale_of(const Box3& b) {
  return std::max({std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z), std::fabs(b.hi.x), std::fabs(b.hi.y),
                   std::fabs(b.hi.z), 0x1p-1000});
}

// A soup of triangles with small-integer vertices on a few planes (axis-aligned or tilted, so that coplanar
// triangles tie exactly), copies with rotated or reversed vertices, shared vertices; scaled by a power of two.
Mesh tie_soup() {
  const int e = *rc::gen::element(0, 0, -3, 30);
  auto s = [&](int v) { return std::ldexp(static_cast<double>(v), e); };
  const int p = *rc::gen::inRange(-2, 3), q = *rc::gen::inRange(-2, 3), c = *rc::gen::inRange(-4, 5);
  const bool tilted = *rc::gen::arbitrary<bool>();
  Mesh m;
  const int count = *rc::gen::inRange(2, 16);
  for (int k = 0; k < count; ++k) {
    if (!m.triangles.empty() && *rc::gen::inRange(0, 4) == 0) {
      auto t = m.triangles[*rc::gen::inRange<std::size_t>(0, m.triangles.size())];
      std::rotate(t.begin(), t.begin() + *rc::gen::inRange(0, 3), t.end());
      if (*rc::gen::arbitrary<bool>()) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
      continue;
    }
    std::array<std::uint32_t, 3> t{};
    for (auto& index : t) {
      if (!m.vertices.empty() && *rc::gen::inRange(0, 3) == 0) {
        index = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, m.vertices.size()));
        continue;
      }
      const int x = *rc::gen::inRange(-4, 5), y = *rc::gen::inRange(-4, 5);
      const int z = *rc::gen::inRange(0, 3) == 0 ? *rc::gen::inRange(-4, 5) : (tilted ? p * x + q * y + c : c);
      index = static_cast<std::uint32_t>(m.vertices.size());
      m.vertices.push_back({s(x), s(y), s(z)});
    }
    m.triangles.push_back(t);
  }
  return m;
}

// A random soup of one scale (shared, repeated and duplicated vertices).
Mesh random_soup() {
  const int e = *rc::gen::element(0, -20, 40, -1000, 600);
  Mesh m;
  auto coordinate = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-16, 17)), e - 3); };
  const int count = *rc::gen::inRange(1, 10);
  for (int k = 0; k < count; ++k) {
    testkit::add_random_triangle(m, coordinate);
  }
  return m;
}

Mesh draw_mesh() {
  switch (*rc::gen::inRange(0, 7)) {
    case 0: return testkit::make_octahedron();
    case 1: return testkit::make_subdivided_cube(2);
    case 2: return testkit::make_icosphere(1);
    case 3: return testkit::make_octahedron(0x1p-1000);
    case 4: return random_soup();
    default: return tie_soup();
  }
}

using testkit::target_point;

// A ray aimed exactly at `target` from a coarse grid point around the mesh (some coordinates shared with the
// target: zero direction components).
Ray aimed_ray(const Box3& bounds, const Vec3& target) {
  const double s = scale_of(bounds);
  auto coord = [&](double t) {
    return *rc::gen::inRange(0, 4) == 0 ? t : std::ldexp(static_cast<double>(*rc::gen::inRange(-24, 25)), -3) * s;
  };
  const Vec3 o{coord(target.x), coord(target.y), coord(target.z)};
  Vec3 d{target.x - o.x, target.y - o.y, target.z - o.z};
  if (d.x == 0 && d.y == 0 && d.z == 0) d = *rc::gen::element(Vec3{s, 0, 0}, Vec3{0, -s, 0}, Vec3{1, 1, 1});
  return {o, d};
}

// Planes for a ray aimed at `target`: through the target itself (its t is the mesh's there: exact ties between
// kinds), through it moved by 2^-60 of the scale (near ties), along a coordinate plane through a mesh vertex,
// or random; normals of small integers (never zero).
std::vector<Plane> draw_planes(const Mesh& mesh, const Vec3& target, double s) {
  std::vector<Plane> planes;
  const int count = *rc::gen::inRange(0, 12);  // from 8 on, nearest_hit's screen runs
  auto normal = [] {
    Vec3 n{0, 0, 0};
    while (n.x == 0 && n.y == 0 && n.z == 0)
      n = {static_cast<double>(*rc::gen::inRange(-3, 4)), static_cast<double>(*rc::gen::inRange(-3, 4)),
           static_cast<double>(*rc::gen::inRange(-3, 4))};
    return n;
  };
  for (int k = 0; k < count; ++k) {
    switch (*rc::gen::inRange(0, 5)) {
      case 0: planes.push_back({target, normal()}); break;
      case 1: {
        const double j = *rc::gen::element(-2.0, -1.0, 1.0, 2.0);
        planes.push_back({{target.x, target.y, target.z + j * std::ldexp(s, -60)}, normal()});
        break;
      }
      case 2: {
        const Vec3 v = mesh.vertices[*rc::gen::inRange<std::size_t>(0, mesh.vertices.size())];
        planes.push_back({v, *rc::gen::element(Vec3{0, 0, 1}, Vec3{0, -1, 0}, Vec3{1, 0, 0})});
        break;
      }
      default: {
        auto c = [&] { return std::ldexp(static_cast<double>(*rc::gen::inRange(-16, 17)), -3) * s; };
        planes.push_back({{c(), c(), c()}, normal()});
      }
    }
  }
  return planes;
}

std::uint64_t rays_checked = 0, kind_ties = 0;

RC_GTEST_PROP(NearestScene, AgreesWithTheExactBruteForceOnMixedScenes, ()) {
  const Mesh mesh = draw_mesh();
  const PreparedMesh prepared(mesh, *rc::gen::element(BvhBuildOptions{},
                                                      BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4}));
  const Box3& bounds = prepared.bvh().bounds();
  const double s = scale_of(bounds);
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::owned, TriangleRule::closed);
  for (int n = 0; n < kBatch; ++n) {
    const Vec3 target = target_point(mesh, bounds, *rc::gen::inRange(0, 4));
    const Ray ray = aimed_ray(bounds, target);
    const std::vector<Plane> planes = draw_planes(mesh, target, s);
    const PlaneSet set(planes);
    const NearestScene scene{&set, &prepared, rule};
    const NearestOptions options{.barycentric = *rc::gen::arbitrary<bool>()};
    const std::optional<SurfaceHit> fast = nearest_hit(ray, scene, options);
    const std::optional<SurfaceHit> exact = nearest_hit_exact(ray, planes, &mesh, rule, options);
    ++rays_checked;
    if (!same_answer(fast, exact))
      RC_FAIL(describe(ray) + ", rule " + std::string(to_string(rule)) + ", " + std::to_string(planes.size()) +
              " planes: module " + describe(fast) + ", brute force " + describe(exact));
    const TracedSceneHit traced = nearest_hit_traced(ray, scene, options);
    RC_ASSERT(same_answer(traced.hit, fast));
    // A plane and a triangle at the same exact t: the plane (counted, so that a run shows them exercised).
    if (fast && fast->kind == SurfaceKind::plane) {
      if (const auto m = nearest_hit(ray, prepared, rule); m && same_bits(m->intersection.t, fast->t)) ++kind_ties;
    }
  }
}

// The scene query is the planes' query and the mesh's combined: the nearer by exact t, a plane on an exact tie.
RC_GTEST_PROP(NearestScene, IsThePlanesAndTheMeshCombined, ()) {
  const Mesh mesh = draw_mesh();
  const PreparedMesh prepared(mesh);
  const Box3& bounds = prepared.bvh().bounds();
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::closed);
  for (int n = 0; n < kBatch; ++n) {
    const Vec3 target = target_point(mesh, bounds, *rc::gen::inRange(0, 4));
    const Ray ray = aimed_ray(bounds, target);
    const std::vector<Plane> planes = draw_planes(mesh, target, scale_of(bounds));
    const PlaneSet set(planes);
    const auto scene = nearest_hit(ray, NearestScene{&set, &prepared, rule});
    const auto plane = nearest_hit(ray, set);
    const auto triangle = nearest_hit(ray, prepared, rule);
    RC_ASSERT(scene.has_value() == (plane.has_value() || triangle.has_value()));
    if (!scene) continue;
    if (scene->kind == SurfaceKind::plane) {
      RC_ASSERT(plane && plane->plane == scene->index && same_bits(plane->t, scene->t));
      RC_ASSERT(!triangle || triangle->intersection.t >= plane->t);
    } else {
      RC_ASSERT(triangle && triangle->triangle == scene->index && same_bits(triangle->intersection.t, scene->t));
      RC_ASSERT(!plane || plane->t >= triangle->intersection.t);
    }
    // Planes alone and a mesh alone through the scene query: their own answers.
    const auto planes_only = nearest_hit(ray, NearestScene{&set, nullptr, rule});
    RC_ASSERT(planes_only.has_value() == plane.has_value());
    if (plane) RC_ASSERT(planes_only->index == plane->plane && same_bits(planes_only->t, plane->t));
    const auto mesh_only = nearest_hit(ray, NearestScene{nullptr, &prepared, rule}, {.barycentric = true});
    RC_ASSERT(mesh_only.has_value() == triangle.has_value());
    if (triangle) {
      RC_ASSERT(mesh_only->index == triangle->triangle && same_bits(mesh_only->t, triangle->intersection.t));
      for (int k = 0; k < 3; ++k) RC_ASSERT(same_bits(mesh_only->barycentric[k], triangle->intersection.barycentric[k]));
    }
  }
}

// The octahedron |x| + |y| + |z − 1| ≤ 2 (scenes/octahedron.json's mesh) and the plane x + y + z = 3, which holds
// its facet (2, 0, 1), (0, 2, 1), (0, 0, 3). Straight down through (0.5, 0.25): the facet at z = 2.25, t = 7.75,
// and the plane at the same point: an exact tie, which the plane wins. Lowered by 2^-20, the plane is behind the
// facet (t = 7.75 + 2^-20) and the facet wins; raised by 2^-50, the plane is nearer, at t = 7.75 − 2^-50.
Mesh octahedron_of_the_scene() {
  Mesh m = testkit::make_octahedron();
  for (Vec3& v : m.vertices) v = {2 * v.x, 2 * v.y, 2 * v.z + 1};
  return m;
}

TEST(NearestScene, APlaneWinsAnExactTieWithATriangle) {
  const PreparedMesh mesh(octahedron_of_the_scene());
  const Ray ray{{0.5, 0.25, 10}, {0, 0, -1}};
  for (const double offset : {0.0, -0x1p-20, 0x1p-50}) {
    const std::vector<Plane> planes{{{0, 0, 3 + offset}, {1, 1, 1}}, {{0, 0, -2}, {0, 0, 1}}};
    const PlaneSet set(planes);
    const auto hit = nearest_hit(ray, NearestScene{&set, &mesh});
    ASSERT_TRUE(hit);
    EXPECT_TRUE(same_answer(hit, nearest_hit_exact(ray, planes, &mesh.mesh()))) << offset;
    if (offset < 0) {
      EXPECT_EQ(hit->kind, SurfaceKind::triangle);
      EXPECT_EQ(hit->t, 7.75);
    } else {
      EXPECT_EQ(hit->kind, SurfaceKind::plane);
      EXPECT_EQ(hit->index, 0u);
      EXPECT_EQ(hit->t, 7.75 - offset);
    }
  }
}

// A triangle nearer than a plane by 2^-54: the triangle (−1, −1, 1), (3, −1, 1), (−1, 3, 1 − 2^-52) holds
// z = 1 − 2^-52·(y + 1)/4, so the ray up the z axis meets it at t = 1 − 2^-54 (a rounding tie: RN gives 1) and the
// plane z = 1 at t = 1. Both t round to 1; the triangle wins, by the certified comparison (no rationals).
TEST(NearestScene, ATriangleNearerThanAPlaneByLessThanAnUlp) {
  Mesh m;
  m.vertices = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1 - 0x1p-52}};
  m.triangles = {{0, 1, 2}};
  const PreparedMesh mesh(m);
  const std::vector<Plane> planes{{{0, 0, 1}, {0, 0, 1}}};
  const PlaneSet set(planes);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  const TracedSceneHit traced = nearest_hit_traced(ray, NearestScene{&set, &mesh});
  ASSERT_TRUE(traced.hit);
  EXPECT_EQ(traced.hit->kind, SurfaceKind::triangle);
  EXPECT_EQ(traced.hit->t, 1.0);
  EXPECT_TRUE(same_answer(traced.hit, nearest_hit_exact(ray, planes, &m)));
  EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 0u);
  EXPECT_GT(traced.comparisons[static_cast<std::size_t>(Stage::compensated)], 0u);
}

// No surfaces, no planes hit, an invalid ray.
TEST(NearestScene, EmptyScenesAndInvalidRays) {
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  EXPECT_FALSE(nearest_hit(ray, NearestScene{}));
  const std::vector<Plane> behind{{{0, 0, -1}, {0, 0, 1}}};
  const PlaneSet set(behind);
  EXPECT_FALSE(nearest_hit(ray, NearestScene{&set, nullptr}));
  EXPECT_THROW((void)nearest_hit({{0, 0, 0}, {0, 0, 0}}, NearestScene{&set, nullptr}), invalid_input);
  EXPECT_THROW((void)nearest_hit_exact({{0, 0, 0}, {0, 0, 0}}, behind, nullptr), invalid_input);
}

// Rounding ties: the octahedron scene's rays at dyadic points hit facets at t = 7 + |x| + |y|; with 1 ≤ |x| < 1.5
// a multiple of 2^-12 and |y| an odd multiple of 2^-50, t is in [8, 9) (ulp 2^-49) and exactly halfway between two
// doubles. Each such t is decided at
// the rounding boundaries in expansions — t_stage expansion, never exact — and equals intersect_exact's.
TEST(NearestScene, RoundingTiesOfATriangleAreDecidedInExpansions) {
  const PreparedMesh mesh(octahedron_of_the_scene());
  int ties = 0;
  for (int i = 0; i < 200; ++i) {
    const double x = 1 + std::ldexp(static_cast<double>((i * 7919) % 2048), -12);
    const double y = std::ldexp(static_cast<double>(((i * 104729) % 997) * 2 + 1), -50);
    const Ray ray{{(i & 1) ? x : -x, (i & 2) ? y : -y, 10}, {0, 0, -1}};
    const TracedSceneHit traced = nearest_hit_traced(ray, NearestScene{nullptr, &mesh});
    ASSERT_TRUE(traced.hit);
    const TriangleIntersection exact = intersect_exact(ray, mesh.mesh().triangle(traced.hit->index));
    EXPECT_TRUE(same_bits(traced.hit->t, exact.t)) << describe(ray);
    EXPECT_NE(traced.t_stage, Stage::exact) << describe(ray);
    const mpq_class t = mpq_class(7) + abs(mpq_class(ray.origin.x)) + abs(mpq_class(ray.origin.y));
    const double down = mpq_class(exact.t) > t ? std::nextafter(exact.t, 0.0) : exact.t;
    const double up = std::nextafter(down, 16.0);
    if ((mpq_class(down) + mpq_class(up)) / 2 == t) ++ties;
  }
  EXPECT_EQ(ties, 200);  // the cases are ties, not only near them
}

// round_quotient_at_boundaries on its own: num/den for small-integer expansions, with candidates at, next to and
// far from RN(num/den), against exact rounding: where it answers, the answer is RN. It may leave a case to the
// exact stage (the expansions' checked sign is conservative: two adjacent components of one sign are
// "uncertain"); how often, for the candidate RN itself, is counted and printed.
std::uint64_t boundary_answered = 0, boundary_left_open = 0;
RC_GTEST_PROP(QuotientBoundary, AnswersOnlyTheCorrectRounding, ()) {
  // q = (2m + 1)/2^k·2^e: exactly halfway between two doubles for m of 53 bits, else near it.
  const std::int64_t m = *rc::gen::inRange<std::int64_t>(1LL << 52, (1LL << 53) - 1);
  const int e = *rc::gen::inRange(-60, 60);
  const int kind = *rc::gen::inRange(0, 3);
  mpq_class value(mpz_class(2 * m + 1));
  if (kind == 1) value += mpq_class(1, 1 << 20);  // just off the midpoint
  if (kind == 2) value = mpq_class(mpz_class(m)) + mpq_class(*rc::gen::inRange(1, 1024), 1024);  // anywhere
  if (e >= 0) value *= mpq_class(mpz_class(1) << e); else value /= mpq_class(mpz_class(1) << -e);
  // num/den with den a small integer (positive or negative) and num = value·den: value as the exact pair (hi, lo)
  // (at most 64 significant bits), num its exact product with den by ExpansionBuilder::scale, as the kernel's
  // expansions are built.
  const int den_int = *rc::gen::element(1, -1, 3, -5, 7);
  auto to_double = [](const mpq_class& v) {
    return round_rational_to_double(mpz_class(v.get_num()).get_str(), mpz_class(v.get_den()).get_str());
  };
  const double hi = to_double(value);
  const mpq_class rest = value - mpq_class(hi);
  const double lo = to_double(rest);
  RC_PRE(mpq_class(lo) == rest);
  detail::Expansion<2> value_expansion;
  detail::ExpansionBuilder::from_pair({hi, lo}, value_expansion);
  detail::ExpansionBuilder builder;
  detail::Expansion<16> num;
  builder.scale(value_expansion, static_cast<double>(den_int), num);
  RC_PRE(builder.exact());
  detail::Expansion<16> den;
  den.component[0] = den_int;
  den.size = 1;
  const double rn = to_double(value);
  const double candidate = *rc::gen::element(rn, std::nextafter(rn, 0.0), std::nextafter(rn, 1e300),
                                             std::nextafter(std::nextafter(rn, 0.0), 0.0));
  const std::optional<double> got = detail::round_quotient_at_boundaries(num, den, den_int > 0 ? 1 : -1, candidate);
  if (got) RC_ASSERT(same_bits(*got, rn));
  if (candidate == rn) ++(got ? boundary_answered : boundary_left_open);
}


TEST(QuotientBoundary, Report) {  // last: after every property of this file
  std::printf("nearest_scene_test: %llu rays against the brute force, %llu plane wins at a triangle's rounded t; "
              "rounding boundaries: %llu answered, %llu left to the exact stage\n",
              static_cast<unsigned long long>(rays_checked), static_cast<unsigned long long>(kind_ties),
              static_cast<unsigned long long>(boundary_answered), static_cast<unsigned long long>(boundary_left_open));
}

}  // namespace
}  // namespace raykernel
