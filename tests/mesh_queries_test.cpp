// The mesh queries (kernel/include/raykernel/mesh_queries.hpp, docs/contract.md §7) against their exact
// references.
//
// - nearest_hit(ray, PreparedMesh) — the BVH walk, the certified cascade, rounded-t ordering with exact ties —
//   must equal nearest_hit_exact, the brute force over every triangle in exact rationals (intersect_exact_rational,
//   the smallest exact t compared in GMP, ties to the smallest index): the same triangle and the same §6 answer
//   bit for bit, or both no hit. Over the closed test meshes of the testkit and random triangle soups (shared
//   vertices, degenerate and duplicated triangles), for rays aimed exactly at vertices, at edge points, at points
//   inside faces, through the bounding box, from points on the surface, under both rules.
//   The 10^6-ray run (mesh_nearest_1M) uses a cheaper brute force, every triangle by the certified `relation`
//   and the hits ordered by exact t in GMP (brute_force below), since the rational reference costs about 10 µs
//   per triangle.
// - inside(point, PreparedMesh) must equal inside_exact for points at vertices, on edges, inside faces, on the
//   axis lines through them (where the axis-aligned ray runs along edges and through vertices), and at random.
// - Ties: 10^5 copies of one triangle must cost no rational comparison (counted by nearest_hit_traced: 99,999
//   before the fix); self-overlapping coplanar fans, near ties, copies under both rules
//   and tie-heavy soups (coplanar small-integer triangles, rotated and reversed copies; every way a tie is settled,
//   rationals included) against nearest_hit_exact; inside against inside_exact with points in those planes.
// - Hand-derived cases (derivations in the comments) check both.
// Each property case draws one mesh and a batch of rays or points (kBatch), so `long` runs cover 10^6 rays
// (mesh_nearest_1M; mesh_inside_100k checks 10^5 points against inside_exact); RapidCheck prints its seed, RC_PARAMS="seed=N" reproduces a run.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/testkit/mesh_rapidcheck.hpp>
#include <raykernel/testkit/meshes.hpp>

#include "mesh/exact_mesh.hpp"
#include "orient/orient_predicates.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace raykernel {
namespace {

constexpr int kBatch = 25;  // rays or points per property case

struct TestMesh {
  std::string name;
  std::unique_ptr<PreparedMesh> prepared;
};

// Small closed meshes (the exact oracle is brute force: microseconds per triangle), with small leaves so that
// the walk has several levels.
const std::vector<TestMesh>& test_meshes() {
  static const std::vector<TestMesh> meshes = [] {
    std::vector<TestMesh> v;
    auto add = [&](std::string name, Mesh m, BvhBuildOptions o = {}) {
      v.push_back({std::move(name), std::make_unique<PreparedMesh>(std::move(m), o)});
    };
    add("octahedron", testkit::make_octahedron());
    add("cube-2", testkit::make_subdivided_cube(2), {.max_leaf_size = 1, .max_leaf_size_hard = 1, .bins = 8});
    add("cube-3-half", testkit::make_subdivided_cube(3, 0.5));
    add("icosphere-1", testkit::make_icosphere(1), {.max_leaf_size = 2, .max_leaf_size_hard = 4, .bins = 16});
    add("terrain-2", testkit::make_terrain(2));
    add("octahedron-tiny", testkit::make_octahedron(0x1p-1000));
    add("octahedron-huge", testkit::make_octahedron(0x1p400));
    return v;
  }();
  return meshes;
}

double scale_of(const Box3& b) {
  return std::max({std::fabs(b.lo.x), std::fabs(b.lo.y), std::fabs(b.lo.z), std::fabs(b.hi.x), std::fabs(b.hi.y),
                   std::fabs(b.hi.z), 0x1p-1000});
}

using testkit::target_point;

// A ray aimed exactly at `target` (when the difference is exact) from a coarse grid point around the mesh; some
// origin coordinates shared with the target (zero direction components), some origins on the surface itself.
Ray aimed_ray(const Mesh& mesh, const Box3& bounds, const Vec3& target) {
  const double s = scale_of(bounds);
  const int from = *rc::gen::inRange(0, 8);
  Vec3 o;
  if (from == 0) {
    o = target_point(mesh, bounds, *rc::gen::inRange(0, 4));
  } else {
    auto coord = [&](double t) {
      return *rc::gen::inRange(0, 4) == 0 ? t : std::ldexp(static_cast<double>(*rc::gen::inRange(-24, 25)), -3) * s;
    };
    o = {coord(target.x), coord(target.y), coord(target.z)};
  }
  Vec3 d{target.x - o.x, target.y - o.y, target.z - o.z};
  if (d.x == 0 && d.y == 0 && d.z == 0) d = *rc::gen::element(Vec3{s, 0, 0}, Vec3{0, -s, 0}, Vec3{1, 1, 1});
  if (*rc::gen::inRange(0, 8) == 0) d = {d.x * 0x1p-30, d.y * 0x1p-30, d.z * 0x1p-30};  // rescaled: exact
  return {o, d};
}

bool same_bits(double x, double y) { return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y); }

std::string describe(const std::optional<MeshHit>& h) {
  if (!h) return "miss";
  return "hit " + std::to_string(h->triangle) + " t=" + std::to_string(h->intersection.t) + " " +
         std::string(to_string(h->intersection.location));
}

bool same_answer(const std::optional<MeshHit>& x, const std::optional<MeshHit>& y) {
  if (!x || !y) return !x && !y;
  const TriangleIntersection &a = x->intersection, &b = y->intersection;
  return x->triangle == y->triangle && a.relation == b.relation && a.location == b.location && a.owned == b.owned &&
         same_bits(a.t, b.t) && same_bits(a.barycentric[0], b.barycentric[0]) &&
         same_bits(a.barycentric[1], b.barycentric[1]) && same_bits(a.barycentric[2], b.barycentric[2]);
}

// One mesh: a test mesh or a fresh soup.
struct Drawn {
  std::unique_ptr<PreparedMesh> own;
  const PreparedMesh* mesh;
};
Drawn draw_mesh() {
  Drawn d;
  if (*rc::gen::inRange(0, 4) == 0) {
    d.own = std::make_unique<PreparedMesh>(testkit::random_soup(), BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4});
    d.mesh = d.own.get();
  } else {
    d.mesh = test_meshes()[*rc::gen::inRange<std::size_t>(0, test_meshes().size())].prepared.get();
  }
  return d;
}

std::uint64_t rays_checked = 0, rays_checked_brute_force = 0, points_checked = 0;
// How the near ties (two t the filter could not order) in AgreesWithTheExactBruteForceOnTies were settled: from the vertices, or by the
// stage of the comparison (so that a run shows each path exercised).
std::uint64_t tie_count[1 + stage_count] = {};

// The brute force with a cheaper per-triangle decision, for the 10^6-ray run: every triangle's relation by the
// certified `relation` (each one checked against exact rationals by triangle_properties_test), every hit's exact
// t = num/den in GMP rationals from the doubles, the smallest exact t winning, ties to the smallest index; the
// winner's §6 answer by intersect_exact (rationals and MPFR).
std::optional<MeshHit> brute_force(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  auto q = [](double x) { return mpq_class(x); };
  std::optional<std::uint32_t> best;
  mpq_class best_t;
  for (std::uint32_t k = 0; k < mesh.triangles.size(); ++k) {
    const Triangle t = mesh.triangle(k);
    if (relation(ray, t, rule).relation != TriangleRelation::hit) continue;
    const std::array<mpq_class, 3> e1{q(t.b.x) - q(t.a.x), q(t.b.y) - q(t.a.y), q(t.b.z) - q(t.a.z)},
        e2{q(t.c.x) - q(t.a.x), q(t.c.y) - q(t.a.y), q(t.c.z) - q(t.a.z)},
        ao{q(t.a.x) - q(ray.origin.x), q(t.a.y) - q(ray.origin.y), q(t.a.z) - q(ray.origin.z)};
    const std::array<mpq_class, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                     e1[0] * e2[1] - e1[1] * e2[0]};
    const mpq_class tk = (ao[0] * n[0] + ao[1] * n[1] + ao[2] * n[2]) /
                         (q(ray.direction.x) * n[0] + q(ray.direction.y) * n[1] + q(ray.direction.z) * n[2]);
    if (best && tk >= best_t) continue;
    best = k;
    best_t = tk;
  }
  if (!best) return std::nullopt;
  return MeshHit{*best, intersect_exact(ray, mesh.triangle(*best), TriangleOptions{.rule = rule})};
}

RC_GTEST_PROP(MeshNearest, AgreesWithTheBruteForce, ()) {
  const Drawn drawn = draw_mesh();
  const PreparedMesh& prepared = *drawn.mesh;
  const Mesh& mesh = prepared.mesh();
  const Box3& bounds = prepared.bvh().bounds();
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::owned, TriangleRule::closed);
  for (int n = 0; n < kBatch; ++n) {
    const int kind = *rc::gen::inRange(0, 4);
    const Ray ray = aimed_ray(mesh, bounds, target_point(mesh, bounds, kind));
    const auto fast = nearest_hit(ray, prepared, rule);
    const auto oracle = brute_force(ray, mesh, rule);
    ++rays_checked_brute_force;
    if (!same_answer(fast, oracle))
      RC_FAIL("ray (" + std::to_string(ray.origin.x) + " " + std::to_string(ray.origin.y) + " " +
              std::to_string(ray.origin.z) + ") + t(" + std::to_string(ray.direction.x) + " " +
              std::to_string(ray.direction.y) + " " + std::to_string(ray.direction.z) + "), rule " +
              std::string(to_string(rule)) + ": BVH " + describe(fast) + ", brute force " + describe(oracle));
  }
}

RC_GTEST_PROP(MeshNearest, AgreesWithTheExactBruteForce, ()) {
  const Drawn drawn = draw_mesh();
  const PreparedMesh& prepared = *drawn.mesh;
  const Mesh& mesh = prepared.mesh();
  const Box3& bounds = prepared.bvh().bounds();
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::owned, TriangleRule::closed);
  for (int n = 0; n < kBatch; ++n) {
    const int kind = *rc::gen::inRange(0, 4);
    const Ray ray = aimed_ray(mesh, bounds, target_point(mesh, bounds, kind));
    const auto fast = nearest_hit(ray, prepared, rule);
    const auto exact = nearest_hit_exact(ray, mesh, rule);
    ++rays_checked;
    if (!same_answer(fast, exact))
      RC_FAIL("ray (" + std::to_string(ray.origin.x) + " " + std::to_string(ray.origin.y) + " " +
              std::to_string(ray.origin.z) + ") + t(" + std::to_string(ray.direction.x) + " " +
              std::to_string(ray.direction.y) + " " + std::to_string(ray.direction.z) + "), rule " +
              std::string(to_string(rule)) + ": BVH " + describe(fast) + ", brute force " + describe(exact));
  }
}

// A soup built for ties: triangles with small-integer vertices on one or two planes —
// axis-aligned (z = c) or tilted (z = p·x + q·y + c), so that coplanar triangles have exactly equal t — many
// copies of some with their vertices rotated or reversed, and fans sharing a vertex; scaled by a power of two
// (tiny scales make stage 3 underflow, so that the rational comparison runs too).
// Rays aimed at vertices, edge points and inside points hit several triangles at one exact t, through faces,
// edges and vertices; the answer must be nearest_hit_exact's under both rules.
Mesh tie_soup() {
  const int e = *rc::gen::element(0, 0, -30, 40, -1000, 600);  // 2^-1000: stage 3 underflows, rationals decide
  Mesh m;
  const int planes = *rc::gen::inRange(1, 3);
  std::vector<std::array<int, 3>> plane(static_cast<std::size_t>(planes));
  for (auto& p : plane)
    p = *rc::gen::element(std::array<int, 3>{0, 0, 0}, std::array<int, 3>{0, 0, 1}, std::array<int, 3>{1, 2, 0},
                          std::array<int, 3>{-3, 1, 2}, std::array<int, 3>{1, 1, -1});
  auto vertex = [&](int x, int y, const std::array<int, 3>& p) {
    m.vertices.push_back({std::ldexp(x, e), std::ldexp(y, e), std::ldexp(p[0] * x + p[1] * y + p[2], e)});
    return static_cast<std::uint32_t>(m.vertices.size() - 1);
  };
  const int count = *rc::gen::inRange(2, 40);
  for (int k = 0; k < count; ++k) {
    const int kind = *rc::gen::inRange(0, 4);
    if (kind == 0 && !m.triangles.empty()) {  // a copy: the same indices rotated, maybe reversed
      auto t = m.triangles[*rc::gen::inRange<std::size_t>(0, m.triangles.size())];
      std::rotate(t.begin(), t.begin() + *rc::gen::inRange(0, 3), t.end());
      if (*rc::gen::arbitrary<bool>()) std::swap(t[1], t[2]);
      m.triangles.push_back(t);
      continue;
    }
    const auto& p = plane[*rc::gen::inRange<std::size_t>(0, plane.size())];
    std::array<std::uint32_t, 3> t{};
    for (auto& index : t) {
      if (kind == 1 && !m.vertices.empty()) {  // shared vertices (possibly off this plane): fans, copies as doubles
        index = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, m.vertices.size()));
      } else {
        index = vertex(*rc::gen::inRange(-4, 5), *rc::gen::inRange(-4, 5), p);
      }
    }
    m.triangles.push_back(t);
  }
  return m;
}

RC_GTEST_PROP(MeshNearest, AgreesWithTheExactBruteForceOnTies, ()) {
  const Mesh mesh = tie_soup();
  const PreparedMesh prepared(mesh, *rc::gen::element(BvhBuildOptions{}, BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4}));
  const Box3& bounds = prepared.bvh().bounds();
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::closed);
  for (int n = 0; n < kBatch; ++n) {
    const Ray ray = aimed_ray(mesh, bounds, target_point(mesh, bounds, *rc::gen::inRange(0, 4)));
    const TracedMeshHit traced = nearest_hit_traced(ray, prepared, rule);
    const auto& fast = traced.hit;
    const auto exact = nearest_hit_exact(ray, mesh, rule);
    ++rays_checked;
    tie_count[0] += traced.ties_without_arithmetic;
    for (int s = 0; s < stage_count; ++s) tie_count[1 + s] += traced.comparisons[static_cast<std::size_t>(s)];
    if (!same_answer(fast, exact) || !same_answer(fast, nearest_hit(ray, prepared, rule)))
      RC_FAIL("ray (" + std::to_string(ray.origin.x) + " " + std::to_string(ray.origin.y) + " " +
              std::to_string(ray.origin.z) + ") + t(" + std::to_string(ray.direction.x) + " " +
              std::to_string(ray.direction.y) + " " + std::to_string(ray.direction.z) + "), rule " +
              std::string(to_string(rule)) + ": BVH " + describe(fast) + ", exact " + describe(exact));
  }
}

RC_GTEST_PROP(MeshInside, AgreesWithTheExactBruteForce, ()) {
  const Drawn drawn = draw_mesh();
  const PreparedMesh& prepared = *drawn.mesh;
  const Mesh& mesh = prepared.mesh();
  const Box3& bounds = prepared.bvh().bounds();
  const double s = scale_of(bounds);
  for (int n = 0; n < kBatch; ++n) {
    Vec3 p = target_point(mesh, bounds, *rc::gen::inRange(0, 4));
    // Move it along one axis (onto the axis line through a vertex or edge point), or not at all.
    const int axis = *rc::gen::inRange(0, 5);
    const double step = std::ldexp(static_cast<double>(*rc::gen::inRange(-8, 9)), -4) * s;
    if (axis == 0) p.x += step;
    if (axis == 1) p.y += step;
    if (axis == 2) p.z += step;
    const PointLocation fast = inside(p, prepared);
    const PointLocation exact = inside_exact(p, mesh);
    ++points_checked;
    RC_ASSERT(fast == exact);
  }
}

// inside on the tie soups: points in the planes of many triangles (on them, on their edges' lines beyond the
// ends, elsewhere in the plane), where the on-surface test meets exact zeros of orient3d in every triangle whose
// box holds the point (decided by exact expansions and filtered planar orientations instead of rationals).
RC_GTEST_PROP(MeshInside, AgreesWithTheExactBruteForceOnFlatSoups, ()) {
  const Mesh mesh = tie_soup();
  const PreparedMesh prepared(mesh, *rc::gen::element(BvhBuildOptions{}, BvhBuildOptions{.max_leaf_size = 1, .max_leaf_size_hard = 2, .bins = 4}));
  const Box3& bounds = prepared.bvh().bounds();
  for (int n = 0; n < kBatch; ++n) {
    Vec3 p;
    if (*rc::gen::inRange(0, 3) == 0) {
      p = target_point(mesh, bounds, *rc::gen::inRange(0, 4));
    } else {  // a point of a triangle's plane: a + (b − a)·i/4 + (c − a')·j/4, on or off the triangle
      const Triangle t = mesh.triangle(*rc::gen::inRange<std::size_t>(0, mesh.triangles.size()));
      const auto q = testkit::edge_point(t.a, t.b, *rc::gen::inRange<std::int64_t>(-4, 9), 2);
      const auto r = q ? testkit::edge_point(*q, t.c, *rc::gen::inRange<std::int64_t>(-4, 9), 2) : std::nullopt;
      p = r ? *r : t.a;
    }
    const PointLocation fast = inside(p, prepared);
    const PointLocation exact = inside_exact(p, mesh);
    ++points_checked;
    RC_ASSERT(fast == exact);
  }
}

// The totals, for the long runs' 10^6 claim (printed whatever filter ran).
class Totals : public ::testing::Environment {
 public:
  void TearDown() override {
    if (rays_checked + rays_checked_brute_force + points_checked > 0)
      std::printf("mesh_queries_test: rays checked against nearest_hit_exact %llu, against the brute force %llu; "
                  "points against inside_exact %llu\n",
                  static_cast<unsigned long long>(rays_checked), static_cast<unsigned long long>(rays_checked_brute_force),
                  static_cast<unsigned long long>(points_checked));
    if (tie_count[0] + tie_count[1] + tie_count[2] + tie_count[3] + tie_count[4] > 0)
      std::printf("mesh_queries_test: near ties settled from the vertices %llu, by stage compensated %llu, "
                  "expansion %llu, exact %llu\n",
                  static_cast<unsigned long long>(tie_count[0]), static_cast<unsigned long long>(tie_count[2]),
                  static_cast<unsigned long long>(tie_count[3]), static_cast<unsigned long long>(tie_count[4]));
  }
};
const auto* const totals = ::testing::AddGlobalTestEnvironment(new Totals);

// ---- the filters of inside() against exact rationals ------------------------------------------------------------

// A coordinate of one of several scales: grid values (many exact zeros and coplanar/collinear configurations),
// values near the filters' range limits, subnormals, huge values, and arbitrary bit patterns.
double filter_coordinate(int scale) {
  switch (*rc::gen::inRange(0, 5)) {
    case 0: return std::ldexp(static_cast<double>(*rc::gen::inRange(-4, 5)), scale);
    case 1: return std::ldexp(static_cast<double>(*rc::gen::inRange<std::int64_t>(-(1LL << 53), 1LL << 53)), scale - 53);
    case 2: return *rc::gen::element(0x1p-300, -0x1p-300, 0x1.fffffffffffffp-301, 0x1p300, 0x1.0000000000001p300,
                                     0x1p-1074, -0x1p-1060, 0x1p-1022, 0.0, -0.0);
    case 3: return std::ldexp(1.0 + std::ldexp(static_cast<double>(*rc::gen::inRange(-8, 9)), -52), scale);
    default: {
      const double x = std::bit_cast<double>(*rc::gen::arbitrary<std::uint64_t>());
      return std::isfinite(x) ? x : 1.0;
    }
  }
}

Vec3 filter_point(int scale) { return {filter_coordinate(scale), filter_coordinate(scale), filter_coordinate(scale)}; }

RC_GTEST_PROP(MeshFilters, Orient3dFilterNeverContradictsTheExactSign, ()) {
  const int scale = *rc::gen::element(0, 0, -20, 30, -280, 280, -1000, 900);
  const Vec3 o = filter_point(scale), a = filter_point(scale), b = filter_point(scale);
  // c: random, or exactly coplanar-ish (a + b − o computed in doubles: often exact on grids).
  const Vec3 c = *rc::gen::arbitrary<bool>() ? filter_point(scale) : Vec3{a.x + b.x - o.x, a.y + b.y - o.y, a.z + b.z - o.z};
  RC_PRE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
  const int filtered = mesh_detail::orient3d_filter(o, a, b, c);
  if (filtered != 0) RC_ASSERT(filtered == detail::exact::det3_sign(o, a, b, c));
  RC_CLASSIFY(filtered != 0, "decided by the filter");
}

RC_GTEST_PROP(MeshFilters, Orient2dFilterNeverContradictsTheExactSign, ()) {
  const int scale = *rc::gen::element(0, 0, -20, 30, -280, 280, -1000, 900, 1020);
  const Vec3 p = filter_point(scale), q = filter_point(scale);
  Vec3 r = *rc::gen::arbitrary<bool>() ? filter_point(scale) : Vec3{2 * q.x - p.x, 2 * q.y - p.y, 2 * q.z - p.z};
  if (*rc::gen::inRange(0, 4) == 0) r.x = *rc::gen::element(p.x, q.x);  // shared coordinates: exact zeros
  if (*rc::gen::inRange(0, 4) == 0) r.y = *rc::gen::element(p.y, q.y);
  if (*rc::gen::inRange(0, 4) == 0) r.z = *rc::gen::element(p.z, q.z);
  RC_PRE(std::isfinite(r.x) && std::isfinite(r.y) && std::isfinite(r.z));
  const int i = *rc::gen::inRange(0, 3), j = (i + 1 + *rc::gen::inRange(0, 2)) % 3;
  const int filtered = mesh_detail::orient2d_filter(p, q, r, i, j);
  const int exact = detail::exact::orient2d_sign(p, q, r, i, j);
  if (filtered != 0) RC_ASSERT(filtered == exact);
  RC_ASSERT(mesh_detail::orient2d_sign(p, q, r, i, j) == exact);  // with its exact-zero shortcut
  RC_CLASSIFY(filtered != 0, "decided by the filter");
}

// ---- hand-derived cases -------------------------------------------------------------------------------------

// The index of the first triangle of `mesh` holding vertex `v` (by index), from the mesh data alone.
std::uint32_t first_triangle_with(const Mesh& mesh, const Vec3& v) {
  for (std::uint32_t k = 0; k < mesh.triangles.size(); ++k)
    for (std::uint32_t i : mesh.triangles[k]) {
      const Vec3& w = mesh.vertices[i];
      if (w.x == v.x && w.y == v.y && w.z == v.z) return k;
    }
  return ~0u;
}

TEST(MeshNearest, HandDerivedOctahedron) {
  const Mesh mesh = testkit::make_octahedron();  // |x| + |y| + |z| = 1
  const PreparedMesh prepared(mesh);
  for (const auto& fn : {+[](const Ray& r, const PreparedMesh& p, TriangleRule rule) { return nearest_hit(r, p, rule); },
                         +[](const Ray& r, const PreparedMesh& p, TriangleRule rule) { return nearest_hit_exact(r, p.mesh(), rule); }}) {
    // From the centre along (1, 1, 1): the face x + y + z = 1 at t = 1/3, barycentric (1/3, 1/3, 1/3).
    auto h = fn({{0, 0, 0}, {1, 1, 1}}, prepared, TriangleRule::owned);
    ASSERT_TRUE(h);
    const Triangle t = mesh.triangle(h->triangle);
    EXPECT_EQ(t.a.x + t.b.x + t.c.x, 1);  // the vertices (1,0,0), (0,1,0), (0,0,1) in some order
    EXPECT_EQ(t.a.y + t.b.y + t.c.y, 1);
    EXPECT_EQ(t.a.z + t.b.z + t.c.z, 1);
    EXPECT_EQ(h->intersection.t, 1.0 / 3);  // RN(1/3)
    EXPECT_EQ(h->intersection.location, TriangleLocation::inside);
    // From (0, 0, 5) down the z axis: the vertex (0, 0, 1) at t = 4. Closed rule: all four triangles around it
    // tie, the smallest index wins. Owned rule: exactly one of them owns the vertex (the ray enters the solid).
    h = fn({{0, 0, 5}, {0, 0, -1}}, prepared, TriangleRule::closed);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->triangle, first_triangle_with(mesh, {0, 0, 1}));
    EXPECT_EQ(h->intersection.t, 4);
    h = fn({{0, 0, 5}, {0, 0, -1}}, prepared, TriangleRule::owned);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->intersection.t, 4);
    EXPECT_EQ(mesh.triangle(h->triangle).a.z + mesh.triangle(h->triangle).b.z + mesh.triangle(h->triangle).c.z, 1);
    // Past the solid: (2, 2, 2) along (1, 0, 0) meets nothing.
    EXPECT_FALSE(fn({{2, 2, 2}, {1, 0, 0}}, prepared, TriangleRule::closed));
    // Behind: from (2, 0, 0) along +x the octahedron lies at t < 0.
    EXPECT_FALSE(fn({{2, 0, 0}, {1, 0, 0}}, prepared, TriangleRule::closed));
  }
}

// Two triangles over the ray (0, 0, 0) + t(0, 0, 1) whose exact t differ by less than half an ulp of 1, so that
// both round to 1: the flat one z = 1 (t = 1) and a tilted one through (−1, −1, 1), (3, −1, 1), (−1, 3, 1 + δ)
// (z = 1 + δ(y + 1)/4, t = 1 + δ/4). The smaller exact t must win whatever the index order.
TEST(MeshNearest, OrdersTiesOfTheRoundedTExactly) {
  for (const double delta : {0x1p-52, -0x1p-52}) {  // t = 1 ± 2^-54: RN gives 1 (for −, the tie goes to even 1)
    for (const bool tilted_first : {false, true}) {
      Mesh m;
      m.vertices = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}, {-1, 3, 1 + delta}};
      const std::array<std::uint32_t, 3> flat{0, 1, 2}, tilted{0, 1, 3};
      m.triangles = tilted_first ? std::vector{tilted, flat} : std::vector{flat, tilted};
      const std::uint32_t flat_index = tilted_first ? 1 : 0, tilted_index = 1 - flat_index;
      const std::uint32_t expected = delta > 0 ? flat_index : tilted_index;
      const Ray ray{{0, 0, 0}, {0, 0, 1}};
      for (const auto& h : {nearest_hit(ray, PreparedMesh(m)), nearest_hit_exact(ray, m)}) {
        ASSERT_TRUE(h);
        EXPECT_EQ(h->triangle, expected) << "delta " << delta << " tilted first " << tilted_first;
        EXPECT_EQ(h->intersection.t, 1.0);
      }
    }
  }
  // Exactly equal t (a duplicated triangle): the smaller index.
  Mesh m;
  m.vertices = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 2}, {0, 1, 2}};
  for (const auto& h : {nearest_hit({{0, 0, 0}, {0, 0, 1}}, PreparedMesh(m)), nearest_hit_exact({{0, 0, 0}, {0, 0, 1}}, m)}) {
    ASSERT_TRUE(h);
    EXPECT_EQ(h->triangle, 0u);
  }
}

// Regression: 100,000 copies of one triangle (the same indices; then its vertices rotated and reversed) all hit at
// the same exact t. The answer is the smallest index; the exact ties must not each cost a comparison in
// rationals (they did: 99,999 of them, 0.4 s per ray) — the same plane is recognised from the vertices, with no
// arithmetic. Counted through nearest_hit_traced, not timed.
TEST(MeshNearest, DuplicatesCostNoRationalComparison) {
  constexpr std::uint32_t copies = 100000;
  for (const bool permuted : {false, true}) {
    Mesh m;
    m.vertices = {{-1, -1, 1}, {3, -1, 1}, {-1, 3, 1}};
    const std::array<std::array<std::uint32_t, 3>, 4> orders{{{0, 1, 2}, {1, 2, 0}, {2, 1, 0}, {0, 2, 1}}};
    for (std::uint32_t k = 0; k < copies; ++k) m.triangles.push_back(permuted ? orders[k % 4] : orders[0]);
    const PreparedMesh prepared(m);
    for (const Ray& ray : {Ray{{0, 0, 0}, {0, 0, 1}}, Ray{{0.25, -0.5, 3}, {0.125, 0.5, -1}}}) {
      const TracedMeshHit traced = nearest_hit_traced(ray, prepared, TriangleRule::owned);
      ASSERT_TRUE(traced.hit);
      EXPECT_EQ(traced.hit->triangle, 0u);
      const TriangleIntersection expected = intersect_exact(ray, m.triangle(0));
      EXPECT_TRUE(same_bits(traced.hit->intersection.t, expected.t));
      EXPECT_EQ(traced.hits, copies);
      EXPECT_EQ(traced.ties, copies - 1);
      EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 0u) << "permuted " << permuted;
      EXPECT_EQ(traced.ties_without_arithmetic, copies - 1) << "permuted " << permuted;
    }
  }
}

// The fan (v0, vi, vi+1) of a polygon that winds over itself: v0 = (0, 0) and vi = (i, ±1) alternately. Every
// triangle contains the points (x, y) with 0 < x ≤ 1/2 and |y| < x/n, so a ray through one of them hits all
// n − 2 triangles at one exact t (a 10^6-gon fanned: seconds per ray, a rational comparison per triangle). In
// the plane z = 0 the ties are settled from the vertices (one axis-aligned plane); in the plane z = x + 2y by the
// exact expansions (small integers: short expansions), never in rationals. Answers against nearest_hit_exact for
// rays through the common region, through the apex v0 (every triangle at its vertex a), through vertices and
// edge points, under both rules (testkit::make_overlapping_fan).
TEST(MeshNearest, OverlappingCoplanarFan) {
  constexpr std::uint32_t n = 300;
  for (const bool tilted : {false, true}) {
    const Mesh m = testkit::make_overlapping_fan(n, tilted);
    const PreparedMesh prepared(m);
    auto above = [&](double x, double y) { return Vec3{x, y, (tilted ? x + 2 * y : 0) + 8}; };
    // Through the common region, straight down and obliquely.
    for (const Ray& ray : {Ray{above(0.5, 0x1p-20), {0, 0, -1}}, Ray{above(0.25, -0x1p-22), {0x1p-10, 0, -1}}}) {
      const TracedMeshHit traced = nearest_hit_traced(ray, prepared, TriangleRule::owned);
      EXPECT_TRUE(same_answer(traced.hit, nearest_hit_exact(ray, m))) << describe(traced.hit);
      ASSERT_TRUE(traced.hit);
      EXPECT_EQ(traced.hit->triangle, 0u);
      EXPECT_EQ(traced.hits, n - 2);
      EXPECT_EQ(traced.ties, n - 3);
      EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 0u) << "tilted " << tilted;
      if (tilted) {
        EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::expansion)], n - 3);
      } else {
        EXPECT_EQ(traced.ties_without_arithmetic, n - 3);
      }
    }
    // Through the apex, a vertex and edge points of each kind.
    std::vector<Ray> rays;
    for (const Vec3& target : {Vec3{0, 0, 0}, Vec3{7, 1, 0}, Vec3{0.5, 0.5, 0}, Vec3{150.5, 0, 0}, Vec3{3.5, -1, 0}}) {
      const Vec3 t{target.x, target.y, tilted ? target.x + 2 * target.y : 0};
      for (const Vec3& o : {Vec3{t.x, t.y, t.z + 4}, Vec3{t.x + 2, t.y - 3, t.z + 5}, Vec3{-1, 0.5, -2}})
        rays.push_back({o, {t.x - o.x, t.y - o.y, t.z - o.z}});
    }
    for (const Ray& ray : rays)
      for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
        const TracedMeshHit traced = nearest_hit_traced(ray, prepared, rule);
        EXPECT_TRUE(same_answer(traced.hit, nearest_hit_exact(ray, m, rule)))
            << "tilted " << tilted << " rule " << to_string(rule) << " ray " << ray.origin.x << " " << ray.origin.y
            << " " << ray.origin.z << ": " << describe(traced.hit);
        EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 0u);
      }
  }
}

// Near ties: the triangles (−1, −1, 1), (3, −1, 1), (−1, 3, 1 + j·2^-60) over the ray (0, 0, 0) + t(0, 0, 1) have
// t = 1 + j·2^-62 (z = 1 + δ(y + 1)/4 at y = 0), which round to 1 for |j| ≤ 256. With j in a scrambled order, some
// triangles repeated (vertices rotated or reversed: exact ties), the smallest j wins, its first index. The filter
// cannot order any two of them (every hit after the first is a near tie); the compensated stage orders them, no
// rationals.
TEST(MeshNearest, NearTiesOfTheRoundedT) {
  Mesh m;
  m.vertices = {{-1, -1, 1}, {3, -1, 1}};
  std::vector<int> js;
  for (int j = -256; j <= 256; j += 8) js.push_back(j);
  for (std::size_t i = 0; i < js.size(); ++i) std::swap(js[i], js[(i * 37 + 11) % js.size()]);
  for (const int j : js) {
    m.vertices.push_back({-1, 3, 1 + std::ldexp(j, -60)});
    const auto v = static_cast<std::uint32_t>(m.vertices.size() - 1);
    m.triangles.push_back({0, 1, v});
    if (j % 3 == 0) m.triangles.push_back({1, v, 0});
    if (j % 5 == 0) m.triangles.push_back({0, v, 1});
  }
  const PreparedMesh prepared(m);
  const Ray ray{{0, 0, 0}, {0, 0, 1}};
  const TracedMeshHit traced = nearest_hit_traced(ray, prepared, TriangleRule::owned);
  EXPECT_TRUE(same_answer(traced.hit, nearest_hit_exact(ray, m))) << describe(traced.hit);
  ASSERT_TRUE(traced.hit);
  EXPECT_EQ(m.vertices[m.triangles[traced.hit->triangle][2]].z, 1 - 0x1p-52);  // j = −256 (rotation: index 2)
  EXPECT_EQ(traced.hit->intersection.t, 1.0);
  EXPECT_EQ(traced.ties, traced.hits - 1);
  EXPECT_GT(traced.comparisons[static_cast<std::size_t>(Stage::compensated)], 0u);
  EXPECT_EQ(traced.comparisons[static_cast<std::size_t>(Stage::exact)], 0u);
  // The same in reverse order: the winner's index changes, the answer is still the brute force's.
  Mesh reversed = m;
  std::reverse(reversed.triangles.begin(), reversed.triangles.end());
  EXPECT_TRUE(same_answer(nearest_hit(ray, PreparedMesh(reversed)), nearest_hit_exact(ray, reversed)));
}

// Copies of one triangle (the same indices, rotated, reversed, or as separate equal vertices) under rays through
// its inside, an edge and a vertex, both rules: the brute force's answer (the smallest index among the hit ones),
// ties settled from the vertices.
TEST(MeshNearest, DuplicatesAgreeWithTheExactBruteForce) {
  Mesh m;
  m.vertices = {{-1, -1, 1}, {3, -1, 1.5}, {-1, 3, 2}, {-1, -1, 1}, {3, -1, 1.5}, {-1, 3, 2}};
  const std::array<std::array<std::uint32_t, 3>, 6> orders{{{0, 1, 2}, {1, 2, 0}, {2, 1, 0}, {0, 2, 1}, {3, 4, 5}, {5, 4, 3}}};
  for (std::uint32_t k = 0; k < 240; ++k) m.triangles.push_back(orders[(k * 7 + k / 6) % 6]);
  const PreparedMesh prepared(m, {.max_leaf_size = 2, .max_leaf_size_hard = 4, .bins = 8});
  for (const Vec3& target : {Vec3{0, 0, 1.375}, Vec3{1, 1, 1.75}, Vec3{1, -1, 1.25}, Vec3{-1, 3, 2}, Vec3{-1, -1, 1}})
    for (const Vec3& o : {Vec3{0, 0, 8}, Vec3{5, -2, -3}, Vec3{target.x, target.y, target.z - 1}})
      for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
        const Ray ray{o, {target.x - o.x, target.y - o.y, target.z - o.z}};
        const TracedMeshHit traced = nearest_hit_traced(ray, prepared, rule);
        EXPECT_TRUE(same_answer(traced.hit, nearest_hit_exact(ray, m, rule)))
            << "target " << target.x << " " << target.y << " " << target.z << " rule " << to_string(rule) << ": "
            << describe(traced.hit);
        EXPECT_EQ(traced.ties_without_arithmetic, traced.ties);
      }
}

TEST(MeshNearest, RejectsInvalidRays) {
  const PreparedMesh prepared(testkit::make_octahedron());
  EXPECT_THROW((void)nearest_hit({{0, 0, 0}, {0, 0, 0}}, prepared), invalid_input);
  EXPECT_THROW((void)nearest_hit({{std::nan(""), 0, 0}, {1, 0, 0}}, prepared), invalid_input);
  EXPECT_THROW((void)nearest_hit_exact({{0, 0, 0}, {0, std::numeric_limits<double>::infinity(), 0}}, prepared.mesh()), invalid_input);
  EXPECT_FALSE(nearest_hit({{0, 0, 0}, {1, 0, 0}}, PreparedMesh(Mesh{})));  // no triangles
}

TEST(MeshInside, HandDerivedOctahedron) {
  const Mesh mesh = testkit::make_octahedron();  // |x| + |y| + |z| ≤ 1, outward normals
  const PreparedMesh prepared(mesh);
  struct Case {
    Vec3 p;
    PointLocation expected;
  };
  const Case cases[] = {
      {{0, 0, 0}, PointLocation::inside},             // the centre
      {{0.25, 0.25, 0.25}, PointLocation::inside},    // sum 3/4
      {{0.5, 0.25, 0.25}, PointLocation::on_surface}, // sum 1, on the face
      {{0.5, 0.5, 0}, PointLocation::on_surface},     // on the edge (1,0,0)–(0,1,0)
      {{1, 0, 0}, PointLocation::on_surface},         // a vertex
      {{0.5, 0.5, 0.25}, PointLocation::outside},     // sum 5/4
      {{0, 0, 0.5}, PointLocation::inside},           // on the z axis: the axis ray runs through the vertex (0,0,1)
      {{0.25, 0.25, 0}, PointLocation::inside},       // in the plane z = 0 of four edges
      {{0.75, 0, 0.125}, PointLocation::inside},      // sum 7/8, its +x ray just under the vertex (1,0,0)
      {{2, 0, 0}, PointLocation::outside},            // outside the box
      {{0, 0, 1 + 0x1p-52}, PointLocation::outside},  // just above the top vertex
      {{0, 0, 1 - 0x1p-53}, PointLocation::inside},   // just below it
  };
  for (const Case& c : cases) {
    EXPECT_EQ(inside(c.p, prepared), c.expected) << c.p.x << " " << c.p.y << " " << c.p.z;
    EXPECT_EQ(inside_exact(c.p, mesh), c.expected) << c.p.x << " " << c.p.y << " " << c.p.z;
  }
  EXPECT_THROW((void)inside({std::nan(""), 0, 0}, prepared), invalid_input);
  // Inward normals (each triangle reversed): the winding number is −1 inside, still inside.
  Mesh reversed = mesh;
  for (auto& t : reversed.triangles) std::swap(t[1], t[2]);
  EXPECT_EQ(winding_number({0, 0, 0}, PreparedMesh(reversed)), -1);
  EXPECT_EQ(winding_number({0, 0, 0}, prepared), 1);
  EXPECT_EQ(inside({0, 0, 0}, PreparedMesh(reversed)), PointLocation::inside);
}

// compare_exact orders exact rationals, in lowest terms or not, by value: 2/6 = 1/3; 1/3 > 3333333333333333/10^16
// (the difference is 1/(3·10^16)); a value 1/10^40 above 7 is above 7; the sign is on the numerator.
TEST(MeshNearest, CompareExactOrdersRationalsByValue) {
  EXPECT_EQ(compare_exact({"1", "3"}, {"2", "6"}), 0);
  EXPECT_EQ(compare_exact({"1", "3"}, {"3333333333333333", "10000000000000000"}), 1);
  EXPECT_EQ(compare_exact({"3333333333333333", "10000000000000000"}, {"1", "3"}), -1);
  EXPECT_EQ(compare_exact({"70000000000000000000000000000000000000001", "10000000000000000000000000000000000000000"},
                          {"7", "1"}),
            1);
  EXPECT_EQ(compare_exact({"-1", "2"}, {"0", "1"}), -1);
  EXPECT_THROW((void)compare_exact({"1", "0"}, {"1", "1"}), std::invalid_argument);
}

}  // namespace
}  // namespace raykernel
