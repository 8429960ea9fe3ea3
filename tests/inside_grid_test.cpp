// inside's point-location grid (kernel/src/mesh/inside_grid.hpp): the closedness test on hand-built meshes, and
// every answer the grid gives — on closed meshes, nested shells, meshes touching along an edge or at a vertex,
// unwelded copies — against the walk and the exact brute force (inside_exact), at points aimed at the grid's own
// cell bounds, at vertices and edges, and anywhere in the box; then the public path on meshes large enough
// to use the grid.
#include <raykernel/mesh_queries.hpp>
#include <raykernel/testkit/meshes.hpp>

#include "mesh/inside_grid.hpp"

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <cstdio>
#include <string>
#include <vector>

namespace raykernel {
namespace {

using mesh_detail::InsideGrid;

Mesh moved(Mesh m, Vec3 by, double scale = 1) {
  for (Vec3& v : m.vertices) v = {v.x * scale + by.x, v.y * scale + by.y, v.z * scale + by.z};
  return m;
}
Mesh flipped(Mesh m) {
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}
Mesh joined(const Mesh& a, const Mesh& b) {
  Mesh m = a;
  const auto offset = static_cast<std::uint32_t>(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return m;
}
// Every triangle with vertices of its own (same positions, nothing shared by index).
Mesh unwelded(const Mesh& a) {
  Mesh m;
  for (const auto& t : a.triangles) {
    const auto k = static_cast<std::uint32_t>(m.vertices.size());
    for (auto i : t) m.vertices.push_back(a.vertices[i]);
    m.triangles.push_back({k, k + 1, k + 2});
  }
  return m;
}

TEST(InsideGrid, ClosednessOfHandBuiltMeshes) {
  const Mesh octahedron = testkit::make_octahedron();
  EXPECT_TRUE(InsideGrid::closed(octahedron));
  EXPECT_TRUE(InsideGrid::closed(testkit::make_subdivided_cube(3)));
  EXPECT_TRUE(InsideGrid::closed(unwelded(octahedron)));  // positions, not indices, are matched
  Mesh open = octahedron;
  open.triangles.pop_back();
  EXPECT_FALSE(InsideGrid::closed(open));
  Mesh one_flipped = octahedron;
  std::swap(one_flipped.triangles[0][1], one_flipped.triangles[0][2]);
  EXPECT_FALSE(InsideGrid::closed(one_flipped));
  // Two copies of one triangle facing the same way leave its edges unmatched; facing opposite ways they close.
  Mesh pair;
  pair.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  pair.triangles = {{0, 1, 2}, {0, 1, 2}};
  EXPECT_FALSE(InsideGrid::closed(pair));
  pair.triangles[1] = {0, 2, 1};
  EXPECT_TRUE(InsideGrid::closed(pair));
  // A degenerate triangle with a repeated vertex adds a matched pair of edges and a loop, which counts for nothing.
  Mesh with_sliver = octahedron;
  with_sliver.triangles.push_back({0, 0, 1});
  EXPECT_TRUE(InsideGrid::closed(with_sliver));
  // −0 and +0 are one position.
  Mesh signed_zero = unwelded(octahedron);
  for (Vec3& v : signed_zero.vertices)
    if (v.x == 0 && (&v - signed_zero.vertices.data()) % 2 == 0) v.x = -0.0;
  EXPECT_TRUE(InsideGrid::closed(signed_zero));
  // A vertex moved by one ulp is another position: the edges around it no longer match.
  Mesh nudged = unwelded(octahedron);
  nudged.vertices[0].x = std::nextafter(nudged.vertices[0].x, 2.0);
  EXPECT_FALSE(InsideGrid::closed(nudged));
  EXPECT_TRUE(InsideGrid::closed(Mesh{}));
}

struct Case {
  std::string name;
  std::unique_ptr<PreparedMesh> prepared;
  InsideGrid grid;
};

// Closed meshes below the public path's threshold (so winding_number walks) with fine grids.
const std::vector<Case>& cases() {
  static const std::vector<Case> v = [] {
    std::vector<Case> out;
    const auto add = [&](std::string name, Mesh m) {
      auto prepared = std::make_unique<PreparedMesh>(std::move(m));
      const PreparedMesh& p = *prepared;
      InsideGrid g = InsideGrid::build(
          p, [&](const Vec3& q) { return winding_number(q, p); }, {.min_triangles = 0, .triangles_per_cell = 0.02});
      out.push_back({std::move(name), std::move(prepared), std::move(g)});
    };
    // (small triangles: an octahedron's triangles' boxes cover its whole box, leaving no free cell)
    const Mesh cube = testkit::make_subdivided_cube(4, 0.5), sphere = testkit::make_icosphere(2);
    add("cube-4", testkit::make_subdivided_cube(4));
    add("icosphere-2", sphere);
    add("nested-same-way", joined(moved(sphere, {0, 0, 0}, 2), sphere));       // winding 2 inside both
    add("nested-shell", joined(moved(sphere, {0, 0, 0}, 2), flipped(sphere)));  // 0 in the hole
    add("cubes-sharing-an-edge", joined(moved(cube, {0.5, 0.5, 0}), moved(cube, {-0.5, -0.5, 0})));
    add("cubes-sharing-a-vertex", joined(moved(cube, {0.5, 0.5, 0.5}), moved(cube, {-0.5, -0.5, -0.5})));
    add("cubes-sharing-a-face", joined(moved(cube, {0.5, 0, 0}), moved(cube, {-0.5, 0, 0})));
    add("unwelded-icosphere", unwelded(testkit::make_icosphere(1)));
    add("inward-icosphere", flipped(sphere));
    add("tiny", moved(testkit::make_icosphere(1), {0, 0, 0}, 0x1p-1000));
    add("huge", moved(testkit::make_subdivided_cube(3), {0x1p500, 0, 0}, 0x1p480));
    return out;
  }();
  return v;
}

std::uint64_t answered_by_grid = 0, checked = 0;

double on_or_near(double x, int ulps) {
  for (int k = 0; k < std::abs(ulps); ++k) x = std::nextafter(x, ulps > 0 ? INFINITY : -INFINITY);
  return x;
}

// A coordinate on axis a: a cell bound (exactly, or a few ulps off), a vertex's, or anywhere in the box.
double coordinate_on(const Case& c, int a) {
  const Box3& b = c.prepared->bvh().bounds();
  const double lo = a == 0 ? b.lo.x : a == 1 ? b.lo.y : b.lo.z, hi = a == 0 ? b.hi.x : a == 1 ? b.hi.y : b.hi.z;
  switch (*rc::gen::inRange(0, 4)) {
    case 0: {
      const auto& planes = c.grid.planes(a);
      return on_or_near(planes[*rc::gen::inRange<std::size_t>(0, planes.size())], *rc::gen::inRange(-2, 3));
    }
    case 1: {
      const Mesh& m = c.prepared->mesh();
      const Vec3& v = m.vertices[*rc::gen::inRange<std::size_t>(0, m.vertices.size())];
      return on_or_near(a == 0 ? v.x : a == 1 ? v.y : v.z, *rc::gen::inRange(-1, 2));
    }
    default: {
      const double u = *rc::gen::inRange(0, 1 << 20) / double(1 << 20);
      return lo + (hi - lo) * u;
    }
  }
}

RC_GTEST_PROP(InsideGrid, EveryAnswerIsTheWalksAndTheExactOne, ()) {
  const Case& c = cases()[*rc::gen::inRange<std::size_t>(0, cases().size())];
  RC_ASSERT(c.grid.usable());
  RC_ASSERT(c.prepared->mesh().triangles.size() < InsideGrid::Options{}.min_triangles);  // winding_number walks
  for (int n = 0; n < 25; ++n) {
    const Vec3 p{coordinate_on(c, 0), coordinate_on(c, 1), coordinate_on(c, 2)};
    const std::optional<std::int64_t> from_grid = c.grid.lookup(p);
    if (!from_grid) continue;
    ++answered_by_grid;
    const std::optional<std::int64_t> walked = winding_number(p, *c.prepared);
    RC_ASSERT(walked.has_value());  // a free cell holds no point of the surface
    RC_ASSERT(*walked == *from_grid);
    if (n % 5 == 0) {  // the exact brute force (rationals, every triangle) on a fifth of them
      ++checked;
      RC_ASSERT(inside_exact(p, c.prepared->mesh()) == (*from_grid != 0 ? PointLocation::inside : PointLocation::outside));
    }
  }
}

// Closed but self-intersecting: an icosphere or a cube whose vertices are moved at random (shared by index, so the
// mesh stays closed whatever the moves), folding it over itself — windings 2, −1, … — and sometimes flattening
// parts of it onto the grid's planes.
RC_GTEST_PROP(InsideGrid, AgreesWithTheWalkOnFoldedClosedMeshes, ()) {
  Mesh m = *rc::gen::element(0, 1) == 0 ? testkit::make_icosphere(1) : testkit::make_subdivided_cube(2);
  const int moves = *rc::gen::inRange(1, 12);
  for (int k = 0; k < moves; ++k) {
    Vec3& v = m.vertices[*rc::gen::inRange<std::size_t>(0, m.vertices.size())];
    const auto step = [] { return *rc::gen::inRange(-8, 9) / 4.0; };
    if (*rc::gen::inRange(0, 4) == 0) v = m.vertices[*rc::gen::inRange<std::size_t>(0, m.vertices.size())];
    else v = {v.x + step(), v.y + step(), v.z + step()};
  }
  RC_ASSERT(InsideGrid::closed(m));
  const PreparedMesh prepared(m);
  const InsideGrid grid = InsideGrid::build(
      prepared, [&](const Vec3& q) { return winding_number(q, prepared); }, {.min_triangles = 0, .triangles_per_cell = 0.01});
  if (!grid.usable()) return;  // (every triangle's box over a fine grid: over budget)
  for (int n = 0; n < 25; ++n) {
    Vec3 p{};
    for (int a = 0; a < 3; ++a) {
      const auto& planes = grid.planes(a);
      const double x = *rc::gen::inRange(0, 2) == 0
                           ? planes[*rc::gen::inRange<std::size_t>(0, planes.size())]
                           : planes.front() + (planes.back() - planes.front()) * (*rc::gen::inRange(0, 1024) / 1024.0);
      (a == 0 ? p.x : a == 1 ? p.y : p.z) = x;
    }
    const std::optional<std::int64_t> from_grid = grid.lookup(p);
    if (!from_grid) continue;
    ++answered_by_grid;
    RC_ASSERT(winding_number(p, prepared) == from_grid);
  }
}

// The property above is vacuous if the grid never answers: it must answer for most points of these meshes'
// boxes, and the free cells must be inside and outside (or in the hole) where the shapes say.
TEST(InsideGrid, AnswersWhereTheShapesSay) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    ASSERT_TRUE(c.grid.usable());
    EXPECT_GT(c.grid.free_share(), 0.3);
    EXPECT_GE(c.grid.components(), 1u);
  }
  const auto at = [](const std::string& name) -> const Case& {
    for (const Case& c : cases())
      if (c.name == name) return c;
    throw std::logic_error(name);
  };
  // Hand-derived: the centre of the nested spheres is inside both (winding 2, outward normals), in the hole of
  // the shell 0 and between its spheres 1; a corner of the box is outside; the inward sphere's centre has −1.
  EXPECT_EQ(at("nested-same-way").grid.lookup({0, 0, 0}).value_or(99), 2);
  EXPECT_EQ(at("nested-shell").grid.lookup({0, 0, 0}).value_or(99), 0);
  EXPECT_EQ(at("nested-shell").grid.lookup({0, 0, 1.5}).value_or(99), 1);   // between the spheres
  EXPECT_EQ(at("icosphere-2").grid.lookup({0.99, 0.99, 0.99}).value_or(99), 0);
  EXPECT_EQ(at("inward-icosphere").grid.lookup({0, 0, 0}).value_or(99), -1);
  EXPECT_EQ(at("cubes-sharing-an-edge").grid.lookup({0.5, 0.5, 0}).value_or(99), 1);
  EXPECT_EQ(at("cubes-sharing-an-edge").grid.lookup({-0.5, 0.5, 0}).value_or(99), 0);
}

// The public path: meshes above the threshold use the grid (built by the first call) and answer as the walk
// (inside(point, Mesh), which never uses it) and the exact brute force do; an open mesh walks every point.
TEST(InsideGrid, PublicPathAgreesWithTheWalkAndTheExactAnswer) {
  const Mesh closed_mesh = testkit::make_icosphere(3);  // 1,280 triangles
  Mesh open_mesh = closed_mesh;
  open_mesh.triangles.pop_back();
  for (const Mesh* m : {static_cast<const Mesh*>(&closed_mesh), static_cast<const Mesh*>(&open_mesh)}) {
    const PreparedMesh prepared(*m);
    const InsideGrid grid =
        InsideGrid::build(prepared, [&](const Vec3& q) { return winding_number(q, prepared); }, {});
    EXPECT_EQ(grid.usable(), m == &closed_mesh);
    std::uint64_t state = 12345;
    const auto next = [&] {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      return static_cast<double>(state >> 11) / 0x1p53;
    };
    int grid_answers = 0;
    for (int n = 0; n < 300; ++n) {
      const Vec3 p{2.2 * next() - 1.1, 2.2 * next() - 1.1, 2.2 * next() - 1.1};
      const PointLocation fast = inside(p, prepared);
      grid_answers += grid.lookup(p).has_value();
      ASSERT_EQ(fast, inside(p, *m)) << p.x << " " << p.y << " " << p.z;
      if (n % 30 == 0) {
        ASSERT_EQ(fast, inside_exact(p, *m)) << p.x << " " << p.y << " " << p.z;
      }
    }
    if (m == &closed_mesh) {
      EXPECT_GT(grid_answers, 100);
    }
  }
}

class Totals : public ::testing::Environment {
 public:
  void TearDown() override {
    std::printf("inside_grid_test: points answered by the grid %llu (checked against the walk), %llu of them also "
                "against inside_exact\n",
                static_cast<unsigned long long>(answered_by_grid), static_cast<unsigned long long>(checked));
  }
};
const auto* const totals = ::testing::AddGlobalTestEnvironment(new Totals);

}  // namespace
}  // namespace raykernel
