// raykernel/mesh_queries.hpp: exact queries on whole triangle meshes (docs/contract.md §7) — the nearest hit
// of a ray and whether a point is inside — through the BVH, always with the brute-force answer.
//
// A PreparedMesh is the fast form: the mesh validated once, its BVH built once, and its triangles copied in
// the BVH's leaf order (so that a leaf's triangles are read from consecutive memory). Build it once and query
// it from any number of threads. The overloads taking a Mesh prepare one for the call.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/bvh.hpp>
#include <raykernel/mesh.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace raykernel {

namespace mesh_detail {
struct InsideGridCache;  // inside's point-location grid, built on the first call (kernel/src/mesh/inside_grid.hpp)
struct InsideGridAccess;
}  // namespace mesh_detail

class PreparedMesh {
 public:
  PreparedMesh() = default;
  // Validates `mesh` (throws invalid_input naming the first bad vertex or triangle, validate(const Mesh&)) and
  // builds its BVH. Degenerate triangles are kept (they are never hit).
  explicit PreparedMesh(Mesh mesh, const BvhBuildOptions& options = {});

  [[nodiscard]] const Mesh& mesh() const noexcept { return mesh_; }
  [[nodiscard]] const MeshBvh& bvh() const noexcept { return bvh_; }
  // The triangles in the order of bvh().triangle_order(): leaf_triangles()[i] is
  // mesh().triangle(bvh().triangle_order()[i]).
  [[nodiscard]] std::span<const Triangle> leaf_triangles() const noexcept { return leaf_triangles_; }

 private:
  Mesh mesh_;
  MeshBvh bvh_;
  detail::LargeVector<Triangle> leaf_triangles_;  // huge pages where the system allows (large_vector.hpp)
  std::shared_ptr<mesh_detail::InsideGridCache> inside_grid_;  // shared by copies (the mesh does not change)
  friend struct mesh_detail::InsideGridAccess;
};

// ---- nearest hit ---------------------------------------------------------------------------------------------

// The nearest triangle a ray hits: its index in the mesh and the §6 answer for it (relation hit, location, t and
// barycentric coordinates, each the exact value rounded to nearest).
struct MeshHit {
  std::uint32_t triangle;
  TriangleIntersection intersection;
};

// docs/contract.md §7: among the triangles whose relation under `rule` is hit (t ≥ 0), the one with the smallest
// exact t, ties to the smallest triangle index; or nothing. Through the BVH (a box the exact ray meets is never
// skipped, bvh.hpp) with the certified ray–triangle cascade, each candidate classified once; two hits are ordered
// by the certified comparison of their exact t (a binary64 filter on the values the relation was decided from,
// double-double enclosures, exact expansions, rationals last; exact ties seen from the vertices without
// arithmetic), never by rounded t; the walk is pruned by a certified upper bound of the best exact t. t and the
// barycentric coordinates are rounded once, for the winner. So the answer is the brute-force one. (The same
// nearest-hit module as planes' and scenes', raykernel/nearest_scene.hpp.)
// Under the owned rule (the default) a ray through a shared edge or vertex of a closed, consistently oriented
// mesh hits exactly one of the triangles around it — except at a silhouette: a ray that only touches the mesh
// along an edge or at a vertex where the surface turns away from it (grazing the outline) has zero or two
// owned hits there, as the moved ray of §6 misses the mesh or crosses it twice. The closed rule hits every
// triangle it touches. Throws invalid_input for an invalid ray (a non-finite component, a zero direction).
// Thread-safe; right in any floating-point environment.
[[nodiscard]] std::optional<MeshHit> nearest_hit(const Ray& ray, const PreparedMesh& mesh,
                                                 TriangleRule rule = TriangleRule::owned);
[[nodiscard]] std::optional<MeshHit> nearest_hit(const Ray& ray, const Mesh& mesh,  // prepares the mesh for the call
                                                 TriangleRule rule = TriangleRule::owned);

// `nearest_hit` plus what it cost: how many candidate triangles the walk returned and which stage decided
// each one's relation (or that it repeated the previous candidate), how many were hit, and how the near ties —
// the hits whose exact t the binary64 filter could not order against the best one's so far (exact ties, and t
// closer than the filter's error) — were ordered: by the same-plane or same-point shortcut, or as a repeat of the
// previous candidate (no arithmetic), or by the stage of the certified comparison of the two exact t that decided
// (compensated, expansion or exact rationals). For tests, the benchmarks and `raykernel nearest --mesh --stats`;
// the same answer as nearest_hit.
struct TracedMeshHit {
  std::optional<MeshHit> hit;
  std::uint64_t candidates = 0;                            // triangles in the leaves the walk returned
  std::array<std::uint64_t, stage_count> relations{};      // candidates whose relation each stage decided
  std::uint64_t repeats = 0;  // candidates with the previous one's vertices (any order): its answer reused
  std::uint64_t hits = 0;                                  // candidates whose relation is hit
  std::uint64_t ties = 0;                                  // near ties: hits the filter could not order
  std::uint64_t ties_without_arithmetic = 0;  // of those, settled by the same-plane or same-point rule, or repeated
  std::array<std::uint64_t, stage_count> comparisons{};    // the other near ties: the stage that ordered the exact t
};
[[nodiscard]] TracedMeshHit nearest_hit_traced(const Ray& ray, const PreparedMesh& mesh,
                                               TriangleRule rule = TriangleRule::owned);

// The reference: every triangle by intersect_exact_rational (exact rationals), the smallest exact t taken in
// rationals, ties to the smallest index. Slow (microseconds per triangle) and obviously right. Throws
// invalid_input for an invalid ray or mesh.
[[nodiscard]] std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const Mesh& mesh,
                                                       TriangleRule rule = TriangleRule::owned);

// The baseline people write: Möller–Trumbore in doubles (intersect_naive) on every triangle of the leaves the
// BVH returns, pruned by the best computed t, the smallest computed t kept (ties to the smallest index). No
// guarantee. No validation beyond the walk's (throws invalid_input for an invalid ray).
[[nodiscard]] std::optional<MeshHit> nearest_hit_naive(const Ray& ray, const PreparedMesh& mesh);

// The sign (−1, 0, +1) of x − y for two exact rationals (decimal strings, denominators nonzero), exactly: for
// ordering exact t values given as text — a plane's (intersect_exact_rational in raykernel.hpp) and a triangle's
// (triangle.hpp). (A scene of planes and a mesh is better asked as one query: raykernel/nearest_scene.hpp.)
// Throws std::invalid_argument on malformed text.
[[nodiscard]] int compare_exact(const Rational& x, const Rational& y);

// ---- inside ---------------------------------------------------------------------------------------------------

enum class PointLocation : std::uint8_t {
  outside,     // winding number 0
  inside,      // winding number ≠ 0
  on_surface,  // the point lies on some triangle (with its boundary)
};
[[nodiscard]] std::string_view to_string(PointLocation location) noexcept;  // "outside", "inside", "on-surface"

// docs/contract.md §7: `on_surface` if the point lies on some triangle — closed, exactly: on the triangle's plane
// and inside it or on its boundary (for a degenerate triangle: on the segment or point it is) — else `inside` or
// `outside` by the exact winding number, the signed count (+1 where den = d·N > 0, −1 where den < 0) of the
// owned crossings (docs/contract.md §6) of a ray from the point. The ray is axis-aligned: along ±x, ±y or ±z,
// towards the nearest face of the mesh's bounding box (a point outside that box is outside). For a closed,
// consistently oriented mesh whose shared vertices are the same doubles the winding number does not depend on
// the direction (§6's consequence), so any direction gives this answer; for another mesh the answer is the one
// of that direction. Outward normals give +1 inside, inward ones −1: both are inside. Throws invalid_input for a
// non-finite point. Thread-safe; right in any floating-point environment. On a closed mesh of 1,024 triangles or
// more the first call builds a point-location grid (kernel/src/mesh/inside_grid.hpp: about 0.15 s per
// 10^6 triangles, once per PreparedMesh and its copies) that answers most points without a walk, with the
// walk's answers; inside(point, Mesh) never builds it.
[[nodiscard]] PointLocation inside(const Vec3& point, const PreparedMesh& mesh);
[[nodiscard]] PointLocation inside(const Vec3& point, const Mesh& mesh);  // prepares the mesh for the call

// The winding number itself (the signed count above), or nothing when the point is on the surface.
[[nodiscard]] std::optional<std::int64_t> winding_number(const Vec3& point, const PreparedMesh& mesh);

// The reference: every triangle in exact rationals — the on-surface test and the crossings of the same ray, by
// intersect_exact_rational (owned rule) and the exact sign of den. Slow (microseconds per triangle) and
// obviously right. Throws invalid_input for an invalid point or mesh.
[[nodiscard]] PointLocation inside_exact(const Vec3& point, const Mesh& mesh);

// Whether `point` lies on `triangle` with its boundary, exactly (the test `inside` uses).
[[nodiscard]] bool point_on_triangle(const Vec3& point, const Triangle& triangle);

// The axis-aligned direction `inside` uses for `point` and a mesh whose vertices span `bounds` (MeshBvh::bounds()):
// ±(1, 0, 0), ±(0, 1, 0) or ±(0, 0, 1), towards the face of `bounds` nearest to the point (a heuristic: a shorter
// walk), ties to the first of +x, −x, +y, −y, +z, −z.
[[nodiscard]] Vec3 inside_ray_direction(const Vec3& point, const Box3& bounds) noexcept;

}  // namespace raykernel
