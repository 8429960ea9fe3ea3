// Closed triangle meshes for tests and benchmarks: an octahedron, subdivided cubes, icospheres and terrains.
//
// Every mesh here is closed (each directed edge a→b of one triangle appears as b→a in exactly one other),
// consistently oriented with outward normals N = (b − a) × (c − a), free of self-intersections and of
// T-junctions, and stores each vertex once, so shared vertices are the same doubles: the meshes for which
// docs/contract.md §6 promises that the owned rule never leaks and never double-counts. Coordinates lie on
// a coarse dyadic grid, so that points on edges and at vertices are exact doubles and rays can be aimed at
// them exactly (see `edge_point`).
#pragma once

#include <raykernel/mesh.hpp>

#include <raykernel/raykernel.hpp>

#include <cstdint>
#include <optional>
#include <vector>

namespace raykernel::testkit {

// Vertices ±radius on the three axes; 8 triangles.
[[nodiscard]] Mesh make_octahedron(double radius = 1.0);

// The cube [−half_size, half_size]^3 with each face cut into n × n squares of two triangles: 12·n²
// triangles, 6n² + 2 vertices. Requires n ≥ 1. With half_size a power of two and n a power of two, every
// coordinate is an exact multiple of half_size/n.
[[nodiscard]] Mesh make_subdivided_cube(int n, double half_size = 1.0);

// The icosahedron subdivided `level` times (each triangle into four; new vertices projected onto the unit
// sphere): 20·4^level triangles. Every vertex is rounded to a multiple of 2^-grid_bits (grid_bits in
// [8, 40]) after projection, once, and shared by index. Requires 0 ≤ level ≤ 10.
[[nodiscard]] Mesh make_icosphere(int level, int grid_bits = 30);

// A solid under a height field: the top is an n × n grid over [0, 1]² with heights in [1/2, 1] (smooth
// hills from `seed`, rounded to multiples of 2^-20), the bottom the same grid at z = 0, and four side
// walls: 4n² + 8n triangles. Requires n ≥ 1.
[[nodiscard]] Mesh make_terrain(int n, std::uint64_t seed = 1);

// A polygon of n ≥ 3 vertices v0 = (0, 0), vi = (i, ±1) alternately, fanned from v0 as (v0, vi, vi+1): n − 2
// triangles that overlap, all through v0, in the plane z = 0 or (`tilted`) z = x + 2y. Every ray through the common
// region meets all of them at one exact t: the worst case of ties for a nearest hit.
[[nodiscard]] Mesh make_overlapping_fan(std::uint32_t n, bool tilted);

// The point a + w·(b − a) for w = k/2^bits, exactly, or nothing when it is not representable (the
// computation in doubles rounded). For aiming rays exactly at edge points of these meshes.
[[nodiscard]] std::optional<Vec3> edge_point(const Vec3& a, const Vec3& b, std::int64_t k, int bits);

// The mesh benchmarks' workload (bench/mesh_bench.cpp, bench/instruction_counts.cpp): `count` rays from points
// uniform on the sphere around the mesh's bounding box (centre the box's, radius its diagonal) towards points
// uniform in the box, from a fixed seed (15); with `points`, also `count` points uniform in the box, drawn in
// the same sequence (the point queries' workload). Requires a mesh with vertices.
[[nodiscard]] std::vector<Ray> benchmark_rays(const Mesh& mesh, std::size_t count, std::vector<Vec3>* points = nullptr);

}  // namespace raykernel::testkit
