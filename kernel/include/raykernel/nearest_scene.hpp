// raykernel/nearest_scene.hpp: the first surface a ray meets in a scene of several kinds — planes, the
// triangles of a mesh and spheres — decided exactly (docs/contract.md §4, §7 and §10 in one query).
//
// The nearest hit of a scene is the surface with the smallest exact t among every plane and triangle whose
// relation is hit and every sphere's smallest root t ≥ 0; an exact tie between kinds goes to the plane, then
// the triangle, then the sphere, a tie within a kind to the smaller index (as nearest_hit does for a plane set
// and for a mesh alone). One query orders every candidate by the certified
// comparison of exact t values (a binary64 filter, double-double enclosures, exact expansions, rationals last)
// and rounds t — and the barycentric coordinates of a triangle, only when asked — once, for the winner. It is
// the same module as nearest_hit(ray, PlaneSet) and nearest_hit(ray, PreparedMesh), which are this query on a
// scene of one kind.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/sphere.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace raykernel {

// The kinds of surface, in the order that settles an exact tie between kinds: a plane before a triangle, a
// triangle before a sphere.
enum class SurfaceKind : std::uint8_t { plane, triangle, sphere };
[[nodiscard]] std::string_view to_string(SurfaceKind kind) noexcept;  // "plane", "triangle", "sphere"

// A scene: prepared planes, a prepared mesh and prepared spheres, any of them absent (null); the mesh's
// triangles count as hit under `rule`. The query only reads them (thread-safe).
struct NearestScene {
  const PlaneSet* planes = nullptr;
  const PreparedMesh* mesh = nullptr;
  TriangleRule rule = TriangleRule::owned;
  const SphereSet* spheres = nullptr;
};

// What to round for the winner besides t.
struct NearestOptions {
  bool barycentric = false;  // a triangle's barycentric coordinates (NaN when not asked, or for a plane)
};

// The nearest surface hit: its kind, its index (the plane's in the PlaneSet, the triangle's in the mesh, the
// sphere's in the SphereSet), t (RN of the exact t; for a sphere its smallest root t ≥ 0) and, for a triangle when asked, RN(πa/den), RN(πb/den), RN(πc/den).
struct SurfaceHit {
  SurfaceKind kind;
  std::size_t index;
  double t;
  Barycentric barycentric;
};

// The certified nearest hit of the scene, or nothing when no surface is hit. Throws invalid_input for an
// invalid ray (a non-finite component, a zero direction). Right in any floating-point environment.
[[nodiscard]] std::optional<SurfaceHit> nearest_hit(const Ray& ray, const NearestScene& scene,
                                                    const NearestOptions& options = {});

// `nearest_hit` plus which stages it needed, over every candidate of every kind: the slowest stage that decided
// a relation, the slowest stage that ordered two t values and how many comparisons each stage decided (a tie
// settled from the vertices, or between two t = 0, counts as filter; a plane set aside by the vectorized screen
// counts one filter comparison, as in TracedNearestHit), and the stage that rounded the winner's t (its relation
// stage when t = 0 exactly; filter on a miss).
struct TracedSceneHit {
  std::optional<SurfaceHit> hit;
  Stage relation_stage = Stage::filter;
  Stage comparison_stage = Stage::filter;
  Stage t_stage = Stage::filter;
  std::array<std::uint64_t, stage_count> comparisons{};
};
[[nodiscard]] TracedSceneHit nearest_hit_traced(const Ray& ray, const NearestScene& scene,
                                                const NearestOptions& options = {});

// The reference: every plane's and triangle's t in exact rationals, the smallest taken exactly (ties: a plane
// before a triangle, then the smaller index), the winner's t (and barycentric coordinates when asked) rounded
// with MPFR. Slow and obviously right. Throws invalid_input for an invalid ray, plane or mesh.
[[nodiscard]] std::optional<SurfaceHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes,
                                                          const Mesh* mesh, TriangleRule rule = TriangleRule::owned,
                                                          const NearestOptions& options = {});
// The same with spheres (each sphere's roots as U ∓ √V in rationals, compared exactly with the others' t).
[[nodiscard]] std::optional<SurfaceHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes,
                                                          const Mesh* mesh, std::span<const Sphere> spheres,
                                                          TriangleRule rule = TriangleRule::owned,
                                                          const NearestOptions& options = {});

}  // namespace raykernel
