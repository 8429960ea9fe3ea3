// The closed test meshes of the testkit (testkit/include/raykernel/testkit/meshes.hpp): the properties the
// owned rule's watertightness relies on, checked directly — every directed edge matched by its reverse in
// exactly one other triangle, outward orientation (positive exact signed volume), no degenerate triangle,
// the stated counts and grids — and edge_point's exactness.
#include <raykernel/io/mesh_file.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <map>
#include <utility>

namespace raykernel::testkit {
namespace {

mpq_class q(double x) { return mpq_class(x); }  // exact: mpq_class(double) converts the bits

// 6·volume = Σ a·(b × c) over the triangles, exactly.
mpq_class six_volume(const Mesh& m) {
  mpq_class sum = 0;
  for (std::size_t k = 0; k < m.triangles.size(); ++k) {
    const Triangle t = m.triangle(k);
    const mpq_class cx = q(t.b.y) * q(t.c.z) - q(t.b.z) * q(t.c.y);
    const mpq_class cy = q(t.b.z) * q(t.c.x) - q(t.b.x) * q(t.c.z);
    const mpq_class cz = q(t.b.x) * q(t.c.y) - q(t.b.y) * q(t.c.x);
    sum += q(t.a.x) * cx + q(t.a.y) * cy + q(t.a.z) * cz;
  }
  return sum;
}

bool degenerate(const Triangle& t) {
  const mpq_class ux = q(t.b.x) - q(t.a.x), uy = q(t.b.y) - q(t.a.y), uz = q(t.b.z) - q(t.a.z);
  const mpq_class vx = q(t.c.x) - q(t.a.x), vy = q(t.c.y) - q(t.a.y), vz = q(t.c.z) - q(t.a.z);
  return uy * vz - uz * vy == 0 && uz * vx - ux * vz == 0 && ux * vy - uy * vx == 0;
}

void expect_closed_outward(const Mesh& m, const char* name) {
  SCOPED_TRACE(name);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e) {
      ASSERT_LT(t[e], m.vertices.size());
      ++directed[{t[e], t[(e + 1) % 3]}];
    }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "edge " << edge.first << "->" << edge.second << " used " << count << " times";
    const auto reverse = directed.find({edge.second, edge.first});
    EXPECT_TRUE(reverse != directed.end() && reverse->second == 1) << "edge " << edge.first << "->" << edge.second
                                                                    << " has no single reverse";
  }
  EXPECT_GT(six_volume(m), 0) << "normals must point outward";
  std::size_t degenerate_count = 0;
  for (std::size_t k = 0; k < m.triangles.size(); ++k) degenerate_count += degenerate(m.triangle(k));
  EXPECT_EQ(degenerate_count, 0u);
}

TEST(TestMeshes, OctahedronIsClosedOutwardWithItsVolume) {
  const Mesh m = make_octahedron(2.0);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.triangles.size(), 8u);
  expect_closed_outward(m, "octahedron");
  // Eight tetrahedra of volume r³/6 (right corner at the origin): 6V = 8r³ = 64 for r = 2.
  EXPECT_EQ(six_volume(m), 64);
}

TEST(TestMeshes, SubdividedCubeIsClosedOutwardWithTheCubesVolume) {
  for (int n : {1, 2, 3, 8}) {
    const Mesh m = make_subdivided_cube(n, 0.5);
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(12 * n * n));
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(6 * n * n + 2));
    expect_closed_outward(m, "cube");
    if (n != 3) {
      EXPECT_EQ(six_volume(m), 6);  // unit cube; n = 3 has inexact thirds, volume only near 1
    }
  }
}

TEST(TestMeshes, IcosphereIsClosedOutwardOnItsGrid) {
  for (int level : {0, 1, 3}) {
    const Mesh m = make_icosphere(level, 24);
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(20) << (2 * level));
    EXPECT_EQ(m.vertices.size(), static_cast<std::size_t>(10 * (1 << (2 * level)) + 2));
    expect_closed_outward(m, "icosphere");
    for (const Vec3& v : m.vertices)
      for (double c : {v.x, v.y, v.z}) EXPECT_EQ(std::ldexp(c, 24), std::nearbyint(std::ldexp(c, 24)));
  }
}

TEST(TestMeshes, TerrainIsAClosedOutwardSolid) {
  for (int n : {1, 2, 7}) {
    const Mesh m = make_terrain(n, 42);
    EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(4 * n * n + 8 * n));
    expect_closed_outward(m, "terrain");
  }
}

// scenes/*.ply are these meshes as files (the README's watertight table is measured on them): each reads back
// as the mesh testkit makes today, bit for bit, so a change to testkit shows here rather than in a stale table.
TEST(TestMeshes, TheMeshFilesInScenesAreTheseMeshes) {
  const std::string scenes = RAYKERNEL_SCENES_DIR;
  const std::pair<const char*, Mesh> files[] = {{"icosphere-3.ply", make_icosphere(3)},
                                                {"cube-8.ply", make_subdivided_cube(8)},
                                                {"terrain-12.ply", make_terrain(12)}};
  for (const auto& [name, expected] : files) {
    const Mesh read = io::read_mesh(scenes + "/" + name);
    ASSERT_EQ(read.vertices.size(), expected.vertices.size()) << name;
    EXPECT_EQ(read.triangles, expected.triangles) << name;
    for (std::size_t i = 0; i < read.vertices.size(); ++i)
      for (int axis = 0; axis < 3; ++axis)
        ASSERT_EQ(std::bit_cast<std::uint64_t>((&read.vertices[i].x)[axis]), std::bit_cast<std::uint64_t>((&expected.vertices[i].x)[axis]))
            << name << " vertex " << i << " axis " << axis;
  }
}

TEST(TestMeshes, EdgePointIsExactOrRefused) {
  // (1, 2, 3) + 3/8·((5, −2, 3) − (1, 2, 3)) = (1 + 1.5, 2 − 1.5, 3) exactly.
  const std::optional<Vec3> p = edge_point({1, 2, 3}, {5, -2, 3}, 3, 3);
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->x, 2.5);
  EXPECT_EQ(p->y, 0.5);
  EXPECT_EQ(p->z, 3.0);
  // 1 + 1/3·(2 − 1) is not a weight k/2^bits; 1/2 of (0 → 2^-1074) is below the smallest subnormal.
  EXPECT_FALSE(edge_point({0, 0, 0}, {0x1p-1074, 0, 0}, 1, 1).has_value());
  // 1 + (2^-60)·1: the sum rounds.
  EXPECT_FALSE(edge_point({1, 0, 0}, {2, 0, 0}, 1, 60).has_value());
}

}  // namespace
}  // namespace raykernel::testkit
