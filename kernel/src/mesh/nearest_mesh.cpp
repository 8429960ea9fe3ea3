// nearest_hit(ray, mesh) (docs/contract.md §7): the BVH walk, nearest leaf first, with the certified ray–triangle
// cascade on each candidate; the reference nearest_hit_exact in rationals; the Möller–Trumbore baseline.
//
// Why the answer is the brute-force one:
//   - Every triangle hit at an exact t ≤ the bound in force is in a returned leaf (bvh.hpp's guarantee).
//   - The bound passed to the walk is +inf until a hit is found, then nextup(RN(t_best)): RN moves a value by
//     at most half an ulp, so t_best < nextup(RN(t_best)); any triangle that could win (t ≤ t_best) is kept.
//   - Two hits are ordered by RN(t): RN is monotone, so RN(t1) < RN(t2) implies t1 < t2; when RN(t1) = RN(t2)
//     the exact t are compared in rationals (mesh/exact_mesh.hpp), and an exact tie goes to the smaller index.
#include <raykernel/mesh_queries.hpp>

#include "mesh/exact_mesh.hpp"
#include "core/fp_environment.hpp"
#include "mesh/bvh_walk.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

void throw_if_invalid(const Ray& ray) {
  if (auto reason = validate(ray)) throw invalid_input(*reason);
}

}  // namespace

std::optional<MeshHit> nearest_hit(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) return std::nullopt;
  return detail::in_default_fp_environment([&]() -> std::optional<MeshHit> {
    detail::BvhWalk walk;
    mesh_detail::start_walk(walk, bvh, ray, 0, inf);
    const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
    const std::span<const Triangle> triangles = mesh.leaf_triangles();
    const TriangleOptions t_only{.rule = rule, .t = true, .barycentric = false};
    bool found = false;
    std::uint32_t best = 0, best_position = 0;
    double best_t = inf, bound = inf;
    BvhLeaf leaf;
    while (next_leaf(walk, bound, leaf)) {
      for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
        const Triangle& tri = triangles[leaf.position + n];
        if (relation(ray, tri, rule).relation != TriangleRelation::hit) continue;
        const std::uint32_t k = leaf.triangles[n];
        const double t = intersect(ray, tri, t_only).t;
        if (found) {
          if (t > best_t) continue;
          if (t == best_t) {
            const int c = detail::exact::compare_triangle_t(ray, tri, triangles[best_position]);
            if (c > 0 || (c == 0 && k > best)) continue;
          }
        }
        found = true;
        best = k;
        best_position = static_cast<std::uint32_t>(leaf.position + n);
        best_t = t;
        bound = std::nextafter(t, inf);
      }
    }
    if (!found) return std::nullopt;
    return MeshHit{best, intersect(ray, triangles[best_position], TriangleOptions{.rule = rule})};
  });
}

std::optional<MeshHit> nearest_hit(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return nearest_hit(ray, PreparedMesh(mesh), rule);
}

std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  if (const auto problem = validate(mesh)) throw invalid_input("mesh: " + *problem);
  std::optional<MeshHit> best;
  Rational best_t;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const ExactTriangleIntersection e = intersect_exact_rational(ray, mesh.triangle(k), rule);
    if (e.intersection.relation != TriangleRelation::hit) continue;
    if (best && detail::exact::compare_rationals(*e.t, best_t) >= 0) continue;  // ties: the smaller index, found first
    best_t = *e.t;
    best = MeshHit{static_cast<std::uint32_t>(k), e.intersection};
  }
  return best;
}

std::optional<MeshHit> nearest_hit_naive(const Ray& ray, const PreparedMesh& mesh) {
  throw_if_invalid(ray);
  BvhRayTraversal walk(mesh.bvh(), ray);
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  std::optional<MeshHit> best;
  double bound = inf;
  while (const auto leaf = walk.next(bound)) {
    for (std::size_t n = 0; n < leaf->triangles.size(); ++n) {
      const TriangleIntersection x = intersect_naive(ray, triangles[leaf->position + n]);
      if (x.relation != TriangleRelation::hit) continue;
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
