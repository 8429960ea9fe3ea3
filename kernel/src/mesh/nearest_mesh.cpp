// nearest_hit(ray, mesh) (docs/contract.md §7): the nearest-hit search (nearest/nearest_search.hpp) on the mesh's
// triangles alone — the BVH walk, nearest leaf first, each candidate classified once, hits ordered by the
// certified comparison of their exact t, t rounded once for the pruning bound and the winner, the barycentric
// coordinates for the winner; the reference nearest_hit_exact in rationals; the Möller–Trumbore baseline.
//
// Cost of ties: a tie used to cost a comparison in rationals (about 5 µs); 100,000 copies of one triangle cost
// 0.4 s per ray, a fan of 10^6 overlapping coplanar triangles seconds. A tie now costs nothing for copies (in any
// vertex order) and for triangles in one axis-aligned plane or crossed at one shared vertex or edge, and a
// stage-2 or stage-3 comparison otherwise; rationals only when those cannot decide (exact ties whose expansions
// exceed the proved length, or an underflow).
#include <raykernel/mesh_queries.hpp>
#include <raykernel/occlusion.hpp>

#include "core/fp_environment.hpp"
#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "core/validation.hpp"
#include "mesh/bvh_walk.hpp"
#include "mesh/exact_mesh.hpp"
#include "nearest/nearest_search.hpp"
#include "triangle/ray_triangle_cascade.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

void throw_if_invalid(const Ray& ray) {
  if (detail::is_valid(ray)) [[likely]]
    return;
  throw invalid_input(*validate(ray));
}

// The search on the mesh alone, for a valid ray in the default environment: the winner with its relation,
// location, owned flag, t and barycentric coordinates (t and the coordinates in one pass of the fast path when
// t was not rounded yet).
template <class Tracer>
[[gnu::always_inline]] inline std::optional<MeshHit> nearest_in_mesh(const Ray& ray, const PreparedMesh& mesh,
                                                                     TriangleRule rule, const RayInterval& interval,
                                                                     Tracer tracer) noexcept {
  detail::NearestSearch<Tracer> search(ray, tracer);
  search.mesh(mesh, rule, interval);
  if (!search.found()) return std::nullopt;
  detail::TriangleCandidate& winner = search.triangle_winner();
  const TriangleClassification& c = winner.classification;
  TriangleIntersection x{c.relation, c.location, c.owned, 0, {}};
  if (!winner.rounded) {
    if (const auto fast = detail::fast_triangle_intersection(ray, *winner.triangle, TriangleOptions{.rule = rule}))
      [[likely]] {
      x.t = fast->intersection.t;
      x.barycentric = fast->intersection.barycentric;
      return MeshHit{static_cast<std::uint32_t>(winner.index), x};
    }
  }
  x.t = winner.round_t();
  x.barycentric = detail::triangle_barycentric(ray, *winner.triangle, rule);
  return MeshHit{static_cast<std::uint32_t>(winner.index), x};
}

RAYKERNEL_MULTIVERSION
std::optional<MeshHit> mesh_untraced(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule,
                                     const RayInterval& interval) noexcept {
  return nearest_in_mesh(ray, mesh, rule, interval, detail::NoTrace{});
}

RAYKERNEL_MULTIVERSION
TracedMeshHit mesh_traced(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule,
                          const RayInterval& interval) noexcept {
  TracedMeshHit traced;
  detail::SearchCounts counts;
  traced.hit = nearest_in_mesh(ray, mesh, rule, interval, detail::Trace{&counts});
  traced.candidates = counts.candidates;
  traced.relations = counts.relations;
  traced.repeats = counts.repeats;
  traced.hits = counts.hits;
  traced.ties = counts.near_ties;
  traced.ties_without_arithmetic = counts.ties_without_arithmetic;
  traced.comparisons = counts.tie_comparisons;
  return traced;
}

}  // namespace

std::optional<MeshHit> nearest_hit(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return mesh_untraced(ray, mesh, rule, RayInterval{}); });
}

std::optional<MeshHit> nearest_hit(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                                   TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&] { return mesh_untraced(ray, mesh, rule, interval); });
}

TracedMeshHit nearest_hit_traced(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return mesh_traced(ray, mesh, rule, RayInterval{}); });
}

TracedMeshHit nearest_hit_traced(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh,
                                 TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&] { return mesh_traced(ray, mesh, rule, interval); });
}

std::optional<MeshHit> nearest_hit(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return nearest_hit(ray, PreparedMesh(mesh), rule);
}

std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  return nearest_hit_exact(ray, RayInterval{}, mesh, rule);
}

// Every triangle in rationals; a hit counts when its rational t lies in the interval (exact::rational_in_interval).
std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const RayInterval& interval, const Mesh& mesh,
                                         TriangleRule rule) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  std::optional<MeshHit> best;
  Rational best_t;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh.triangle(k), rule);
    if (e.intersection.relation != TriangleRelation::hit) continue;
    if (!detail::exact::rational_in_interval(*e.t, interval)) continue;
    if (best && detail::exact::compare_rationals(*e.t, best_t) >= 0) continue;  // ties: the smaller index, found first
    best_t = *e.t;
    best = MeshHit{static_cast<std::uint32_t>(k), e.intersection};
  }
  return best;
}

std::optional<MeshHit> nearest_hit_naive(const Ray& ray, const PreparedMesh& mesh) {
  return nearest_hit_naive(ray, RayInterval{}, mesh);
}

// The baseline with an interval: the walk from t_min to t_max, and the computed t compared with the bounds.
std::optional<MeshHit> nearest_hit_naive(const Ray& ray, const RayInterval& interval, const PreparedMesh& mesh) {
  throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  BvhRayTraversal walk(mesh.bvh(), ray, interval.t_min, interval.t_max);
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  std::optional<MeshHit> best;
  double bound = inf;
  while (const auto leaf = walk.next(bound)) {
    for (std::size_t n = 0; n < leaf->triangles.size(); ++n) {
      const TriangleIntersection x = intersect_naive(ray, triangles[leaf->position + n]);
      if (x.relation != TriangleRelation::hit || x.t < interval.t_min || x.t > interval.t_max) continue;
      const std::uint32_t k = leaf->triangles[n];
      if (best && (x.t > best->intersection.t || (x.t == best->intersection.t && k > best->triangle))) continue;
      best = MeshHit{k, x};
      bound = x.t;  // not certified: the baseline prunes by its own t
    }
  }
  return best;
}

int compare_exact(const Rational& x, const Rational& y) {
  if (x.denominator.empty() || x.numerator.empty() || y.denominator.empty() || y.numerator.empty() ||
      x.denominator == "0" || y.denominator == "0")
    throw std::invalid_argument("compare_exact: malformed rational");
  return detail::exact::compare_rationals(x, y);
}

}  // namespace raykernel
