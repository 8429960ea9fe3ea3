// raykernel/occlusion.hpp: rays with an interval, occlusion (any-hit) and segments between two points, on
// triangle meshes, exactly (docs/contract.md §8).
//
// A ray may carry an interval [t_min, t_max] (Embree's tnear/tfar): a triangle counts only when its exact
// t = num/den (docs/contract.md §6) lies in it, decided by the sign of num − b·den against the bound b as given —
// a rounded t is never compared. `occluded` asks whether anything blocks a ray in its interval, or the open
// segment between two points, and stops at the first blocker. A segment's direction q − p is taken exactly
// (it is generally not a double): every decision is the sign of an orient3d-type determinant of the doubles
// given, or of a tie-break polynomial in them, never of a rounded difference.
//
// Coplanar and degenerate triangles never count, in any of these queries. Under the owned rule (the default) a
// ray or a segment through a shared edge or vertex of a closed, consistently oriented mesh whose shared vertices
// are the same doubles is blocked by exactly one of the triangles around it (two or none at a silhouette): a
// shadow ray never leaks through a mesh and a parity count never double-counts.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/interval.hpp>
#include <raykernel/mesh_queries.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {

// Why p, q are not a valid segment: a non-finite coordinate ("segment p y is NaN") or p = q as values (0 equals
// −0: "segment endpoints are equal"); or nothing.
[[nodiscard]] std::optional<std::string> validate_segment(const Vec3& p, const Vec3& q);

// ---- rays with an interval -----------------------------------------------------------------------------------

// docs/contract.md §8: nearest_hit (mesh_queries.hpp) among the triangles whose exact t lies in `interval`: the
// smallest exact t there under `rule`, ties to the smallest index. The interval is compared exactly (the BVH
// walk starts and stops at its bounds; each hit's t is ordered against a bound by the certified comparison of
// two quotients, t against b/1). Throws invalid_input for an invalid ray or interval.
[[nodiscard]] std::optional<MeshHit> nearest_hit(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                                                 TriangleRule rule = TriangleRule::owned);

// nearest_hit_traced and nearest_hit_naive (mesh_queries.hpp) with an interval: the same counts, the same
// baseline (its computed t compared with the bounds in doubles: no guarantee).
[[nodiscard]] TracedMeshHit nearest_hit_traced(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                                               TriangleRule rule = TriangleRule::owned);
[[nodiscard]] std::optional<MeshHit> nearest_hit_naive(const Ray& ray, const RayInterval& interval,
                                                       const PreparedMesh& mesh);

// docs/contract.md §8: whether some triangle passes `rule` (owned by default) at an exact t in `interval`
// ([0, +inf] without one). Any-hit: the BVH walk stops at the first such triangle it finds, whichever it is.
// Throws invalid_input for an invalid ray or interval. Thread-safe; right in any floating-point environment.
[[nodiscard]] bool occluded(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule = TriangleRule::owned);
[[nodiscard]] bool occluded(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                            TriangleRule rule = TriangleRule::owned);

// docs/contract.md §8: whether some triangle meets the open segment from p to q (0 < t < 1 along the exact
// direction q − p; the endpoints never count) under `rule`. A triangle counts when p and q lie strictly on
// opposite sides of its plane and the line p → q passes through it under the rule, the owned tie-break using the
// exact q − p. Throws invalid_input for non-finite coordinates or p = q. Thread-safe; right in any floating-point
// environment.
[[nodiscard]] bool occluded(const Vec3& p, const Vec3& q, const PreparedMesh& mesh,
                            TriangleRule rule = TriangleRule::owned);

// The same for one triangle: whether it meets the open segment from p to q under `rule` (certified).
[[nodiscard]] bool segment_meets(const Vec3& p, const Vec3& q, const Triangle& triangle,
                                 TriangleRule rule = TriangleRule::owned);

// ---- all hits ----------------------------------------------------------------------------------------------------

// Every triangle a ray hits within its interval, and the signed count of its owned crossings there.
struct MeshHits {
  std::vector<MeshHit> hits;  // each triangle once, ordered by exact t, ties by triangle index (§6's answer each)
  // Σ sign(den) over the triangles the owned rule lets through at an exact t in the interval (whatever the rule
  // asked for the list): +1 where the ray enters through the front (d·N > 0), −1 through the back. For a ray from
  // outside a closed, consistently oriented mesh with [0, +inf], the winding number of the far end minus the
  // near end's: 0.
  std::int64_t crossings = 0;
};

// trimesh's multiple_hits and Open3D's count_intersections, exact: every triangle whose relation under `rule` is
// hit at an exact t in `interval`, each once, ordered by the certified comparison of their exact t (ties to the
// smaller index), with t and the barycentric coordinates rounded as §6; and the signed count of owned crossings.
// Throws invalid_input for an invalid ray or interval.
[[nodiscard]] MeshHits all_hits(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                                TriangleRule rule = TriangleRule::owned);

// ---- the references ------------------------------------------------------------------------------------------
// Every triangle in exact rationals (intersect_exact_rational for rays; for segments, §6's values with the exact
// direction q − p in rationals, and 0 < num/den < 1 tested as rationals). Slow and obviously right. Throw
// invalid_input for invalid input.

[[nodiscard]] std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh,
                                                       TriangleRule rule = TriangleRule::owned);
[[nodiscard]] MeshHits all_hits_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh,
                                      TriangleRule rule = TriangleRule::owned);
[[nodiscard]] bool occluded_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh,
                                  TriangleRule rule = TriangleRule::owned);
[[nodiscard]] bool occluded_exact(const Vec3& p, const Vec3& q, const Mesh& mesh,
                                  TriangleRule rule = TriangleRule::owned);
[[nodiscard]] bool segment_meets_exact(const Vec3& p, const Vec3& q, const Triangle& triangle,
                                       TriangleRule rule = TriangleRule::owned);

}  // namespace raykernel
