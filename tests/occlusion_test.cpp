// Rays with an interval, occlusion and segments (<raykernel/occlusion.hpp>, docs/contract.md §8): hand-derived
// cases (t exactly at a bound and an ulp beside it, a ray starting on a triangle, segments ending exactly on a
// face, passing exactly through vertices and edges of a closed mesh, lying in a face's plane, with q − p not a
// double; every invalid bound), the contract's sample through the CLI's stream code, and RapidCheck properties:
// the certified answers equal the exact brute force (rationals) on generated meshes, rays, intervals and segments,
// and the segment parity property (a segment from inside a closed mesh to outside crosses an odd number of owned
// triangles; inside to inside or outside to outside, an even number), with inside-ness from the exact winding
// number (inside()).
#include "invalid_reason.hpp"

#include <raykernel/occlusion.hpp>
#include <raykernel/testkit/meshes.hpp>

#include "commands/mesh_file.hpp"
#include "commands/mesh_nearest.hpp"
#include "commands/mesh_occluded.hpp"

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();
constexpr double denorm_min = std::numeric_limits<double>::denorm_min();

double up(double x) { return std::nextafter(x, inf); }
double down(double x) { return std::nextafter(x, -inf); }

// The triangle (0,0,0), (1,0,0), (0,1,0) in the plane z = 0, N = (0, 0, 1).
Mesh unit_triangle_mesh() { return Mesh{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}}; }

using test::invalid_reason;

// ---- Intervals: the exact t against the bounds ------------------------------------------------------------------

TEST(RayInterval, ATIsComparedExactlyAtTheBoundAndAnUlpBeside) {
  const PreparedMesh mesh(unit_triangle_mesh());
  // From (1/4, 1/4, 1) along −z: the plane z = 0 at t = 1 exactly.
  const Ray ray{{0.25, 0.25, 1}, {0, 0, -1}};
  EXPECT_TRUE(occluded(ray, RayInterval{1, 1}, mesh));
  EXPECT_TRUE(occluded(ray, RayInterval{0, 1}, mesh));
  EXPECT_TRUE(occluded(ray, RayInterval{1, inf}, mesh));
  EXPECT_FALSE(occluded(ray, RayInterval{up(1), inf}, mesh));
  EXPECT_FALSE(occluded(ray, RayInterval{0, down(1)}, mesh));
  ASSERT_TRUE(nearest_hit(ray, RayInterval{1, 1}, mesh).has_value());
  EXPECT_EQ(nearest_hit(ray, RayInterval{1, 1}, mesh)->intersection.t, 1.0);
  EXPECT_FALSE(nearest_hit(ray, RayInterval{up(1), 2}, mesh).has_value());
}

TEST(RayInterval, ATThatIsNotADoubleIsNeverRoundedToCompare) {
  const PreparedMesh mesh(unit_triangle_mesh());
  // Along (0, 0, −3) from z = 1: t = 1/3 exactly. 1/3 = 0.010101..._2; its 53 significant bits end in 1 and the
  // next bit is 0, so RN(1/3) < 1/3 (checked below in rationals, not assumed).
  const Ray ray{{0.25, 0.25, 1}, {0, 0, -3}};
  const double rn = 1.0 / 3.0;
  ASSERT_LT(mpq_class(rn), mpq_class(1, 3));
  ASSERT_GT(mpq_class(up(rn)), mpq_class(1, 3));
  EXPECT_FALSE(occluded(ray, RayInterval{0, rn}, mesh));  // t > RN(t): a rounded comparison would say blocked
  EXPECT_TRUE(occluded(ray, RayInterval{0, up(rn)}, mesh));
  EXPECT_TRUE(occluded(ray, RayInterval{rn, inf}, mesh));  // t_min < t
  EXPECT_FALSE(occluded(ray, RayInterval{up(rn), inf}, mesh));
  // nearest_hit agrees, and still reports RN(t).
  EXPECT_FALSE(nearest_hit(ray, RayInterval{0, rn}, mesh).has_value());
  const auto hit = nearest_hit(ray, RayInterval{rn, up(rn)}, mesh);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->intersection.t, rn);
  EXPECT_EQ(nearest_hit_exact(ray, RayInterval{0, rn}, mesh.mesh()).has_value(), false);
  EXPECT_EQ(occluded_exact(ray, RayInterval{rn, inf}, mesh.mesh()), true);
}

TEST(RayInterval, ARayStartingOnATriangleIsBlockedByItOnlyFromTMinZero) {
  const PreparedMesh mesh(unit_triangle_mesh());
  const Ray on{{0.25, 0.25, 0}, {0, 0, 1}};  // t = 0
  EXPECT_TRUE(occluded(on, mesh));
  EXPECT_TRUE(occluded(on, RayInterval{0, 0}, mesh));
  EXPECT_TRUE(occluded(on, RayInterval{-0.0, 0}, mesh));  // −0 is 0
  EXPECT_FALSE(occluded(on, RayInterval{denorm_min, inf}, mesh));
  EXPECT_FALSE(occluded_exact(on, RayInterval{denorm_min, inf}, mesh.mesh()));
}

TEST(RayInterval, TheNearestHitInTheIntervalSkipsNearerTriangles) {
  // Two copies of the unit triangle, at z = 0 (index 0) and z = −1 (index 1); the ray from z = 1 down meets them
  // at t = 1 and t = 2.
  Mesh m = unit_triangle_mesh();
  m.vertices.insert(m.vertices.end(), {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}});
  m.triangles.push_back({3, 4, 5});
  const PreparedMesh mesh(m);
  const Ray ray{{0.25, 0.25, 1}, {0, 0, -1}};
  EXPECT_EQ(nearest_hit(ray, mesh)->triangle, 0u);
  EXPECT_EQ(nearest_hit(ray, RayInterval{up(1), inf}, mesh)->triangle, 1u);
  EXPECT_EQ(nearest_hit(ray, RayInterval{up(1), inf}, mesh)->intersection.t, 2.0);
  EXPECT_EQ(nearest_hit(ray, RayInterval{0, 1.5}, mesh)->triangle, 0u);
  EXPECT_FALSE(nearest_hit(ray, RayInterval{1.25, 1.75}, mesh).has_value());
  EXPECT_FALSE(nearest_hit(ray, RayInterval{up(2), inf}, mesh).has_value());
  EXPECT_EQ(nearest_hit(ray, RayInterval{2, 2}, mesh)->triangle, 1u);
}

TEST(RayInterval, ThroughASharedEdgeOfAClosedMeshTheOwnedRuleBlocksOnce) {
  const Mesh octahedron = testkit::make_octahedron();
  const PreparedMesh mesh(octahedron);
  // From outside towards the midpoint of the edge (1,0,0)–(0,1,0): t = 1 exactly.
  const Ray ray{{1, 1, 0}, {-0.5, -0.5, 0}};
  int owned = 0, closed = 0;
  for (std::size_t k = 0; k < octahedron.triangles.size(); ++k) {
    const TriangleClassification c = relation(ray, octahedron.triangle(k), TriangleRule::owned);
    owned += c.relation == TriangleRelation::hit && c.owned;
    closed += relation(ray, octahedron.triangle(k), TriangleRule::closed).relation == TriangleRelation::hit;
  }
  EXPECT_EQ(closed, 4);  // two at the entry edge, two at the exit edge
  EXPECT_EQ(owned, 2);   // one each
  EXPECT_TRUE(occluded(ray, RayInterval{0, 1}, mesh));  // the entry, exactly at t_max
  EXPECT_FALSE(occluded(ray, RayInterval{0, down(1)}, mesh));
  EXPECT_TRUE(occluded(ray, RayInterval{0, 1}, mesh, TriangleRule::closed));
}

TEST(RayInterval, EveryInvalidBoundIsNamed) {
  EXPECT_EQ(validate(RayInterval{nan_value, 1}), "t_min is NaN");
  EXPECT_EQ(validate(RayInterval{-1, 1}), "t_min is negative");
  EXPECT_EQ(validate(RayInterval{-denorm_min, 1}), "t_min is negative");
  EXPECT_EQ(validate(RayInterval{inf, inf}), "t_min is +inf");
  EXPECT_EQ(validate(RayInterval{-inf, 1}), "t_min is -inf");
  EXPECT_EQ(validate(RayInterval{0, nan_value}), "t_max is NaN");
  EXPECT_EQ(validate(RayInterval{0, -1}), "t_max is negative");
  EXPECT_EQ(validate(RayInterval{2, 1}), "t_min is greater than t_max");
  EXPECT_EQ(validate(RayInterval{up(1), 1}), "t_min is greater than t_max");
  EXPECT_EQ(validate(RayInterval{-0.0, 0}), std::nullopt);
  EXPECT_EQ(validate(RayInterval{0, -0.0}), std::nullopt);
  EXPECT_EQ(validate(RayInterval{denorm_min, denorm_min}), std::nullopt);
  EXPECT_EQ(validate(RayInterval{0, inf}), std::nullopt);
  const PreparedMesh mesh(unit_triangle_mesh());
  const Ray ray{{0, 0, 1}, {0, 0, -1}};
  EXPECT_EQ(invalid_reason([&] { (void)occluded(ray, RayInterval{2, 1}, mesh); }), "t_min is greater than t_max");
  EXPECT_EQ(invalid_reason([&] { (void)nearest_hit(ray, RayInterval{nan_value, 1}, mesh); }), "t_min is NaN");
  EXPECT_EQ(invalid_reason([&] { (void)occluded(Ray{{0, 0, 1}, {0, 0, 0}}, mesh); }),
            "ray direction is the zero vector");
}

// ---- All hits ----------------------------------------------------------------------------------------------------

std::vector<std::uint32_t> indices(const MeshHits& h) {
  std::vector<std::uint32_t> k;
  for (const MeshHit& x : h.hits) k.push_back(x.triangle);
  return k;
}

TEST(AllHits, EachTriangleOnceInExactOrderWithTheSignedOwnedCrossings) {
  const Mesh octahedron = testkit::make_octahedron();
  const PreparedMesh mesh(octahedron);
  // Along −x from (2, 0, 0): in through the vertex +x at t = 1, out through −x at t = 3. Entering, d·N < 0 for the
  // outward normals (−1); leaving, d·N > 0 (+1): 0 in all.
  const Ray ray{{2, 0, 0}, {-1, 0, 0}};
  const MeshHits owned = all_hits(ray, RayInterval{}, mesh);
  ASSERT_EQ(owned.hits.size(), 2u);
  EXPECT_EQ(owned.hits[0].intersection.t, 1.0);
  EXPECT_EQ(owned.hits[1].intersection.t, 3.0);
  EXPECT_EQ(owned.crossings, 0);
  // The closed rule: the four faces around each vertex, each group by index; the count stays the owned one.
  const MeshHits closed = all_hits(ray, RayInterval{}, mesh, TriangleRule::closed);
  ASSERT_EQ(closed.hits.size(), 8u);
  for (std::size_t k = 0; k < 8; ++k) EXPECT_EQ(closed.hits[k].intersection.t, k < 4 ? 1.0 : 3.0);
  for (std::size_t k = 0; k + 1 < 8; ++k) {
    if (k != 3) {
      EXPECT_LT(closed.hits[k].triangle, closed.hits[k + 1].triangle);
    }
  }
  EXPECT_EQ(closed.crossings, 0);
  // From the centre: one way out, +1; in [1.5, inf] from outside, the exit alone.
  EXPECT_EQ(all_hits(Ray{{0, 0, 0}, {1, 0, 0}}, RayInterval{}, mesh).crossings, 1);
  const MeshHits exit = all_hits(ray, RayInterval{1.5, inf}, mesh);
  ASSERT_EQ(exit.hits.size(), 1u);
  EXPECT_EQ(exit.hits[0].intersection.t, 3.0);
  EXPECT_EQ(exit.crossings, 1);
  EXPECT_EQ(indices(all_hits_exact(ray, RayInterval{}, octahedron, TriangleRule::closed)), indices(closed));
}

// ---- Segments ----------------------------------------------------------------------------------------------------

// The number of triangles of `mesh` that meet the open segment p → q under `rule`, each asked alone.
int blockers(const Vec3& p, const Vec3& q, const Mesh& mesh, TriangleRule rule) {
  int count = 0;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) count += segment_meets(p, q, mesh.triangle(k), rule);
  return count;
}

TEST(Segment, ThroughAVertexOfAClosedMeshExactlyOneOwnedBlocker) {
  const Mesh octahedron = testkit::make_octahedron();  // vertices ±1 on the axes
  // From the centre through the vertex (1, 0, 0) at t = 1/2: four triangles meet there.
  EXPECT_EQ(blockers({0, 0, 0}, {2, 0, 0}, octahedron, TriangleRule::owned), 1);
  EXPECT_EQ(blockers({0, 0, 0}, {2, 0, 0}, octahedron, TriangleRule::closed), 4);
  // q − p = 2 + 2^-1074 is not a double: the owned tie-break uses the exact direction.
  const Vec3 p{-denorm_min, 0, 0}, q{2, 0, 0};
  ASSERT_NE(mpq_class(q.x - p.x), mpq_class(q.x) - mpq_class(p.x));
  EXPECT_EQ(blockers(p, q, octahedron, TriangleRule::owned), 1);
  EXPECT_EQ(blockers(p, q, octahedron, TriangleRule::closed), 4);
  EXPECT_TRUE(occluded(p, q, PreparedMesh(octahedron)));
}

TEST(Segment, ThroughAnEdgeOfAClosedMeshExactlyOneOwnedBlocker) {
  const Mesh octahedron = testkit::make_octahedron();
  // Through the midpoint (1/2, 1/2, 0) of the edge (1,0,0)–(0,1,0), at t = 1/2.
  EXPECT_EQ(blockers({0, 0, 0}, {1, 1, 0}, octahedron, TriangleRule::owned), 1);
  EXPECT_EQ(blockers({0, 0, 0}, {1, 1, 0}, octahedron, TriangleRule::closed), 2);
  // A direction that is not a double: p = (−2^-1074, −2^-1074, 0), through the same edge point.
  const Vec3 p{-denorm_min, -denorm_min, 0}, q{1, 1, 0};
  EXPECT_EQ(blockers(p, q, octahedron, TriangleRule::owned), 1);
  EXPECT_EQ(blockers(p, q, octahedron, TriangleRule::closed), 2);
  // From outside to outside through two edges (entry and exit): two owned blockers, one at each.
  EXPECT_EQ(blockers({1, 1, 0}, {-1, -1, 0}, octahedron, TriangleRule::owned), 2);
  EXPECT_EQ(blockers({1, 1, 0}, {-1, -1, 0}, octahedron, TriangleRule::closed), 4);
}

TEST(Segment, AnEndpointOnAFaceDoesNotCount) {
  const Mesh octahedron = testkit::make_octahedron();
  const PreparedMesh mesh(octahedron);
  // The face x + y + z = 1 (x, y, z > 0) contains (1/4, 1/4, 1/2) exactly.
  for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
    EXPECT_FALSE(occluded({0, 0, 0}, {0.25, 0.25, 0.5}, mesh, rule));
    EXPECT_FALSE(occluded({0.25, 0.25, 0.5}, {0, 0, 0}, mesh, rule));  // p on the face
    EXPECT_TRUE(occluded({0, 0, 0}, {0.25, 0.25, up(0.5)}, mesh, rule));  // an ulp beyond the face
    EXPECT_FALSE(occluded({0, 0, 0}, {0.25, 0.25, down(0.5)}, mesh, rule));
    // From the face outwards: the endpoint on the face never counts; nothing else is met.
    EXPECT_FALSE(occluded({0.25, 0.25, 0.5}, {1, 1, 1}, mesh, rule));
    EXPECT_FALSE(occluded_exact({0, 0, 0}, {0.25, 0.25, 0.5}, octahedron, rule));
    EXPECT_TRUE(occluded_exact({0, 0, 0}, {0.25, 0.25, up(0.5)}, octahedron, rule));
  }
}

TEST(Segment, InAFacesPlaneItIsNeverBlockedByThatFace) {
  const Mesh octahedron = testkit::make_octahedron();
  const PreparedMesh mesh(octahedron);
  // Both endpoints inside the face x + y + z = 1: the segment lies on the face (coplanar: never counts), and
  // stays strictly on the inner side of every other face's plane.
  for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
    EXPECT_FALSE(occluded({0.25, 0.25, 0.5}, {0.5, 0.25, 0.25}, mesh, rule));
    EXPECT_FALSE(occluded_exact({0.25, 0.25, 0.5}, {0.5, 0.25, 0.25}, octahedron, rule));
  }
}

TEST(Segment, InvalidEndpointsAreNamed) {
  EXPECT_EQ(validate_segment({0, 0, 0}, {0, 0, 0}), "segment endpoints are equal (p = q)");
  EXPECT_EQ(validate_segment({0, -0.0, 0}, {-0.0, 0, 0}), "segment endpoints are equal (p = q)");
  EXPECT_EQ(validate_segment({0, nan_value, 0}, {1, 0, 0}), "segment p y is NaN");
  EXPECT_EQ(validate_segment({0, 0, 0}, {1, 0, -inf}), "segment q z is -inf");
  EXPECT_EQ(validate_segment({0, 0, 0}, {denorm_min, 0, 0}), std::nullopt);
  const PreparedMesh mesh(unit_triangle_mesh());
  EXPECT_EQ(invalid_reason([&] { (void)occluded(Vec3{1, 2, 3}, Vec3{1, 2, 3}, mesh); }),
            "segment endpoints are equal (p = q)");
}

TEST(Segment, HugeDifferencesBeyondTheDoubleRangeAreExact) {
  // q − p = 2^1024 (beyond the largest double) along z, crossing z = 0 inside the triangle at t = 1/2.
  const PreparedMesh mesh(unit_triangle_mesh());
  const double big = 0x1p1023;
  EXPECT_TRUE(occluded({0.25, 0.25, -big}, {0.25, 0.25, big}, mesh));
  EXPECT_TRUE(occluded_exact({0.25, 0.25, -big}, {0.25, 0.25, big}, mesh.mesh()));
  EXPECT_FALSE(occluded({2, 0.25, -big}, {2, 0.25, big}, mesh));
}

// ---- The contract's sample (tests/data/contract-cases/occluded-sample) through the CLI's stream code ------------

std::vector<std::string> lines_of(const std::string& text) {
  std::istringstream s(text);
  std::vector<std::string> out;
  for (std::string l; std::getline(s, l);) out.push_back(l);
  return out;
}

std::vector<std::string> file_lines(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return lines_of(s.str());
}

// Answers compared as docs/contract.md §8 says: the words exactly, a T as the double it reads back to with the
// sign of a zero, any invalid line for an invalid one.
bool same_answer(const std::string& got, const std::string& want) {
  std::istringstream g(got), w(want);
  std::vector<std::string> gt, wt;
  for (std::string t; g >> t;) gt.push_back(t);
  for (std::string t; w >> t;) wt.push_back(t);
  if (wt.empty() || gt.empty()) return false;
  if (wt[0] == "invalid") return gt[0] == "invalid";
  if (wt[0] != "hit") return gt == wt;
  if (gt.size() != 3 || gt[0] != "hit" || gt[1] != wt[1]) return false;
  const double a = std::strtod(gt[2].c_str(), nullptr), b = std::strtod(wt[2].c_str(), nullptr);
  return a == b && std::signbit(a) == std::signbit(b);
}

TEST(OccludedSample, EveryLineIsTheContractsAnswer) {
  const std::string dir = std::string(RAYKERNEL_CASES_DIR) + "/occluded-sample";
  std::ostringstream mesh_errors;
  std::optional<Mesh> mesh = cli::read_mesh_file("occluded", dir + "/mesh.obj", mesh_errors);
  ASSERT_TRUE(mesh.has_value()) << mesh_errors.str();
  const PreparedMesh prepared(*mesh);
  int checked = 0;
  for (const TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
    const std::string suffix = rule == TriangleRule::owned ? ".expected" : ".closed.expected";
    for (const bool segment : {false, true}) {
      std::ifstream in(dir + (segment ? "/segments.txt" : "/rays.txt"));
      std::ostringstream out, err;
      cli::MeshOccludedCounts counts;
      const cli::MeshOccludedOptions options{.rule = rule, .segment = segment};
      EXPECT_EQ(cli::mesh_occluded_stream(in, out, err, prepared, options, counts), 1);  // invalid lines included
      const auto got = lines_of(out.str()), want = file_lines(dir + (segment ? "/segments" : "/rays") + suffix);
      ASSERT_EQ(got.size(), want.size());
      for (std::size_t k = 0; k < got.size(); ++k, ++checked)
        EXPECT_TRUE(same_answer(got[k], want[k])) << (segment ? "segment " : "ray ") << k + 1 << ": " << got[k]
                                                  << ", want " << want[k];
    }
    std::ifstream in(dir + "/rays.txt");
    std::ostringstream out, err;
    cli::MeshNearestCounts counts;
    EXPECT_EQ(cli::mesh_nearest_stream(in, out, err, prepared, cli::MeshNearestOptions{.rule = rule}, counts), 1);
    const auto got = lines_of(out.str()), want = file_lines(dir + "/nearest" + suffix);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < got.size(); ++k, ++checked)
      EXPECT_TRUE(same_answer(got[k], want[k])) << "nearest " << k + 1 << ": " << got[k] << ", want " << want[k];
  }
  EXPECT_EQ(checked, 1800);
}

// ---- Properties: certified == exact brute force -----------------------------------------------------------------

// A mesh for the properties: a closed one (octahedron, subdivided cube) scaled by a power of two, plus a few
// triangles on a coarse grid through it (coplanar with faces, sharing vertices, degenerate), so that rays and
// segments aimed at grid points meet vertices, edges, coplanar faces and exact ties.
struct Generated {
  Mesh mesh;
  int scale;
};

Generated generated_mesh() {
  const int scale = *rc::gen::element(0, 0, 3, -7, 200, -300);
  Mesh m = *rc::gen::arbitrary<bool>() ? testkit::make_octahedron(1) : testkit::make_subdivided_cube(2, 1);
  const int extra = *rc::gen::inRange(0, 6);
  auto grid = [] { return *rc::gen::inRange(-4, 5) / 4.0; };
  for (int k = 0; k < extra; ++k) {
    std::array<std::uint32_t, 3> t{};
    for (auto& index : t) {
      if (*rc::gen::arbitrary<bool>()) {
        index = static_cast<std::uint32_t>(*rc::gen::inRange<std::size_t>(0, m.vertices.size()));
      } else {
        m.vertices.push_back({grid(), grid(), grid()});
        index = static_cast<std::uint32_t>(m.vertices.size() - 1);
      }
    }
    m.triangles.push_back(t);
  }
  for (Vec3& v : m.vertices) v = {std::ldexp(v.x, scale), std::ldexp(v.y, scale), std::ldexp(v.z, scale)};
  return {std::move(m), scale};
}

// A point on the grid of quarters in [−2, 2]^3 (vertices, edge midpoints and face points of the meshes above), a
// vertex of the mesh, or a point with random low bits; scaled like the mesh.
Vec3 generated_point(const Generated& g) {
  switch (*rc::gen::inRange(0, 4)) {
    case 0: return g.mesh.vertices[*rc::gen::inRange<std::size_t>(0, g.mesh.vertices.size())];
    case 1: {
      auto c = [&] { return std::ldexp(*rc::gen::inRange(-1 << 20, 1 << 20), g.scale - 19); };
      return {c(), c(), c()};
    }
    default: {
      auto c = [&] { return std::ldexp(*rc::gen::inRange(-8, 9), g.scale - 2); };
      return {c(), c(), c()};
    }
  }
}

std::string text(const Vec3& v) {
  std::ostringstream s;
  s << std::hexfloat << v.x << ' ' << v.y << ' ' << v.z;
  return s.str();
}

// A bound near the exact t of some triangle the ray's line crosses: RN(t), an ulp either side, or 0 and +inf.
double bound_near_a_t(const Ray& ray, const Mesh& mesh) {
  const std::size_t k = *rc::gen::inRange<std::size_t>(0, mesh.triangles.size());
  const TriangleIntersection x = intersect(ray, mesh.triangle(k));
  double t = std::isnan(x.t) ? 1 : std::fabs(x.t);
  if (std::isinf(t)) t = 1;
  switch (*rc::gen::inRange(0, 6)) {
    case 0: return 0;
    case 1: return up(t);
    case 2: return down(t) < 0 ? 0 : down(t);
    default: return t;
  }
}

RC_GTEST_PROP(OcclusionCertified, RaysWithIntervalsAgreeWithTheExactBruteForce, ()) {
  const Generated g = generated_mesh();
  const PreparedMesh prepared(g.mesh);
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::closed);
  int bounded_hits = 0;  // hits found in an interval that is not [0, +inf]
  for (int n = 0; n < 8; ++n) {
    const Vec3 o = generated_point(g), target = generated_point(g);
    const Vec3 d{target.x - o.x, target.y - o.y, target.z - o.z};
    const Ray ray{o, d};
    if (validate(ray)) continue;
    double a = bound_near_a_t(ray, g.mesh), b = *rc::gen::arbitrary<bool>() ? inf : bound_near_a_t(ray, g.mesh);
    if (a > b) std::swap(a, b);
    if (std::isinf(a)) a = 0;
    const RayInterval interval{a, b};
    const auto fast = nearest_hit(ray, interval, prepared, rule);
    const auto exact = nearest_hit_exact(ray, interval, g.mesh, rule);
    bounded_hits += exact && (a > 0 || b < inf);
    const std::string where = "ray " + text(o) + " + t·" + text(d) + " in [" + std::to_string(a) + ", " +
                              std::to_string(b) + "], rule " + std::string(to_string(rule));
    RC_ASSERT(fast.has_value() == exact.has_value());
    if (fast) {
      RC_ASSERT(fast->triangle == exact->triangle);
      RC_ASSERT(fast->intersection.t == exact->intersection.t);
    }
    const bool blocked = occluded(ray, interval, prepared, rule);
    if (blocked != exact.has_value()) RC_FAIL("occluded disagrees: " + where);
    const MeshHits all = all_hits(ray, interval, prepared, rule), all_exact = all_hits_exact(ray, interval, g.mesh, rule);
    if (indices(all) != indices(all_exact) || all.crossings != all_exact.crossings)
      RC_FAIL("all_hits disagrees: " + where);
    for (std::size_t k = 0; k < all.hits.size(); ++k) RC_ASSERT(all.hits[k].intersection.t == all_exact.hits[k].intersection.t);
    RC_ASSERT(all.hits.empty() == !exact.has_value());
    if (exact) RC_ASSERT(all.hits.front().triangle == exact->triangle);
  }
  RC_CLASSIFY(bounded_hits > 0, "a hit within a bounded interval");
}

RC_GTEST_PROP(OcclusionCertified, SegmentsAgreeWithTheExactBruteForce, ()) {
  const Generated g = generated_mesh();
  const PreparedMesh prepared(g.mesh);
  const TriangleRule rule = *rc::gen::element(TriangleRule::owned, TriangleRule::closed);
  int blocked = 0;
  for (int n = 0; n < 8; ++n) {
    const Vec3 p = generated_point(g), q = generated_point(g);
    if (validate_segment(p, q)) continue;
    int meets = 0;
    for (std::size_t k = 0; k < g.mesh.triangles.size(); ++k) {
      const Triangle t = g.mesh.triangle(k);
      const bool fast = segment_meets(p, q, t, rule), exact = segment_meets_exact(p, q, t, rule);
      if (fast != exact)
        RC_FAIL("segment " + text(p) + " → " + text(q) + ", triangle " + std::to_string(k) + ", rule " +
                std::string(to_string(rule)) + ": certified " + std::to_string(fast) + ", exact " + std::to_string(exact));
      meets += exact;
    }
    blocked += meets > 0;
    RC_ASSERT(occluded(p, q, prepared, rule) == (meets > 0));
    RC_ASSERT(occluded(q, p, prepared, rule) == (meets > 0));  // symmetric (docs/contract.md §8, decided)
  }
  RC_CLASSIFY(blocked > 0, "some segment occluded");
}

// ---- Property: segment parity on closed meshes ------------------------------------------------------------------

RC_GTEST_PROP(OcclusionParity, ASegmentCrossesAnOddNumberOfOwnedTrianglesExactlyWhenItLeavesTheSolid, ()) {
  // Closed, consistently oriented meshes with shared vertices as the same doubles: the octahedron, a subdivided
  // cube, and the contract sample's L-prism with a diamond (two components, non-convex, fanned hexagons).
  static const Mesh sample = [] {
    std::ostringstream errors;
    return *cli::read_mesh_file("occluded", std::string(RAYKERNEL_CASES_DIR) + "/occluded-sample/mesh.obj", errors);
  }();
  const int which = *rc::gen::inRange(0, 3);
  const int scale = *rc::gen::element(0, 0, 5, -9, 300, -400);
  Mesh m = which == 0 ? testkit::make_octahedron(1) : which == 1 ? testkit::make_subdivided_cube(2, 1) : sample;
  for (Vec3& v : m.vertices) v = {std::ldexp(v.x, scale), std::ldexp(v.y, scale), std::ldexp(v.z, scale)};
  const PreparedMesh prepared(m);
  const Generated g{m, scale};
  int leaving = 0, several = 0;
  for (int n = 0; n < 6; ++n) {
    // p mostly near the middle (inside), q anywhere: both kinds of pairs are common.
    const Vec3 p = *rc::gen::arbitrary<bool>() ? generated_point(g) : Vec3{std::ldexp(*rc::gen::inRange(-3, 4), scale - 2),
                                                                           std::ldexp(*rc::gen::inRange(-3, 4), scale - 2),
                                                                           std::ldexp(*rc::gen::inRange(-1, 3), scale - 3)};
    const Vec3 q = generated_point(g);
    if (validate_segment(p, q)) continue;
    const PointLocation lp = inside(p, prepared), lq = inside(q, prepared);
    if (lp == PointLocation::on_surface || lq == PointLocation::on_surface) continue;
    int crossings = 0;
    for (std::size_t k = 0; k < m.triangles.size(); ++k) crossings += segment_meets(p, q, m.triangle(k));
    leaving += lp != lq;
    several += crossings > 1;
    if ((crossings % 2 == 1) != (lp != lq))
      RC_FAIL("segment " + text(p) + " → " + text(q) + ": " + std::to_string(crossings) + " owned crossings, from " +
              std::string(to_string(lp)) + " to " + std::string(to_string(lq)));
    RC_ASSERT(occluded(p, q, prepared) == (crossings > 0));
  }
  RC_CLASSIFY(leaving > 0, "a segment leaving the solid");
  RC_CLASSIFY(several > 0, "a segment with several crossings");
}

}  // namespace
}  // namespace raykernel
