// raykernel/closest_point.hpp: the exact closest point of a triangle mesh to a point (docs/contract.md §11) —
// the triangle, the point, the squared distance as an exact rational, and every rounded value correctly
// rounded — through the BVH, and the brute-force reference.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/mesh_queries.hpp>

#include <cstdint>
#include <string_view>

namespace raykernel {

// Where on its triangle the closest point lies: a vertex, the inside of an edge, or the inside of the face.
// For a degenerate triangle (its vertices on a line or one point) a vertex or an edge: the segment it is.
enum class ClosestFeature : std::uint8_t { vertex, edge, face };
[[nodiscard]] std::string_view to_string(ClosestFeature feature) noexcept;  // "vertex", "edge", "face"

// docs/contract.md §11. Among the points of every triangle (closed: its edges and vertices included; a degenerate
// triangle is the segment or point it is) the one nearest to `query`, by the exact Euclidean distance; among
// triangles at the same exact distance, the smallest index.
struct ClosestPoint {
  std::uint32_t triangle = 0;                      // its index in the mesh
  ClosestFeature feature = ClosestFeature::face;   // where on that triangle the point lies
  std::uint8_t corner = 0;  // vertex: 0, 1, 2 for a, b, c; edge: 0, 1, 2 for ab, bc, ca; face: 0
  Vec3 point{};             // the exact closest point, each coordinate rounded to nearest (ties to even)
  Rational squared_distance_exact;  // |query − point|², exactly (the point's exact coordinates)
  double squared_distance = 0;      // that rational rounded to nearest: +inf when it exceeds the doubles
  double distance = 0;              // √(exact squared distance), rounded once to nearest
};

// The closest point through the BVH (nearest box first, pruned by an upper bound of the best exact squared
// distance, so that a box is skipped only when every point of it is provably farther). Each candidate triangle
// is measured in interval arithmetic (every binary64 operation rounded to nearest, then widened by one ulp
// outwards, so each interval holds the exact value); the closest feature is taken from the interval signs when
// they are certain, in exact rationals otherwise (and always for a degenerate triangle). Candidates whose
// intervals overlap the best one are ordered exactly: two whose closest feature is the same vertex or the same
// edge (the same doubles) are at the same distance without arithmetic; others in rationals. The winner is
// evaluated once in rationals and rounded. So the answer is the brute-force one. Throws invalid_input for a
// non-finite query point and for a mesh without triangles. Thread-safe; right in any floating-point
// environment.
[[nodiscard]] ClosestPoint closest_point(const Vec3& query, const PreparedMesh& mesh);
[[nodiscard]] ClosestPoint closest_point(const Vec3& query, const Mesh& mesh);  // prepares the mesh for the call

// closest_point plus what it cost: the triangles measured, those decided in rationals because an interval
// sign was uncertain (or the triangle is degenerate), and the candidates ordered in rationals at the end.
struct TracedClosestPoint {
  ClosestPoint closest;
  std::uint64_t candidates = 0;        // triangles measured
  std::uint64_t exact_features = 0;    // of those, measured in rationals
  std::uint64_t exact_comparisons = 0; // near-tied candidates ordered in rationals
};
[[nodiscard]] TracedClosestPoint closest_point_traced(const Vec3& query, const PreparedMesh& mesh);

// The signed distance: closest_point's distance, negative when inside(query, mesh) is inside, zero on the surface
// (then the distance is 0 too), positive outside — Open3D's convention (compute_signed_distance). The sign is
// the exact `inside`, so it is meaningful for a closed mesh (for another, it is that of `inside`'s winding
// number, raykernel/mesh_queries.hpp).
[[nodiscard]] double signed_distance(const Vec3& query, const PreparedMesh& mesh);
// The same from closest_point(query, mesh)'s answer, `closest` (only the sign is computed).
[[nodiscard]] double signed_distance(const Vec3& query, const PreparedMesh& mesh, const ClosestPoint& closest);

// The reference: every triangle in exact rationals, the smallest exact squared distance, ties to the smallest
// index. Slow (microseconds per triangle) and obviously right. Throws invalid_input as closest_point.
[[nodiscard]] ClosestPoint closest_point_exact(const Vec3& query, const Mesh& mesh);

// The baseline people write: the closest point of every triangle in doubles (Ericson's Voronoi-region
// algorithm, Real-Time Collision Detection §5.1.5) over the leaves of the same BVH, pruned by the best computed
// squared distance. Fills triangle, feature, corner, point, squared_distance and distance (√ of the computed
// squared distance); squared_distance_exact stays empty. No guarantee.
[[nodiscard]] ClosestPoint closest_point_naive(const Vec3& query, const PreparedMesh& mesh);

}  // namespace raykernel
