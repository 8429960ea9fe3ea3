// nearest_hit(ray, mesh) (docs/contract.md §7): the BVH walk, nearest leaf first, with the certified ray–triangle
// cascade on each candidate; the reference nearest_hit_exact in rationals; the Möller–Trumbore baseline.
//
// Why the answer is the brute-force one:
//   - Every triangle hit at an exact t ≤ the bound in force is in a returned leaf (bvh.hpp's guarantee).
//   - The bound passed to the walk is +inf until a hit is found, then nextup(RN(t_best)): RN moves a value by
//     at most half an ulp, so t_best < nextup(RN(t_best)); any triangle that could win (t ≤ t_best) is kept.
//   - Two hits are ordered by RN(t): RN is monotone, so RN(t1) < RN(t2) implies t1 < t2; when RN(t1) = RN(t2)
//     the exact t are compared in rationals (exact/exact_mesh.hpp), and an exact tie goes to the smaller index.
#include <raykernel/mesh_queries.hpp>

#include "exact/exact_mesh.hpp"
#include "fp_environment.hpp"
#include "mesh/bvh_walk.hpp"
#include "triangle/ray_triangle_cascade.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

void throw_if_invalid(const Ray& ray) {
  if (auto reason = validate(ray)) throw invalid_input(*reason);
}

// Records what a traced query cost (TracedMeshHit); NoTrace compiles to nothing.
struct NoTrace {
  void candidate(Stage) noexcept {}
  void hit() noexcept {}
  void tie() noexcept {}
  void tie_without_arithmetic() noexcept {}
  void comparison(Stage) noexcept {}
};
struct Trace {
  TracedMeshHit* out;
  void candidate(Stage s) noexcept {
    ++out->candidates;
    ++out->relations[static_cast<std::size_t>(s)];
  }
  void hit() noexcept { ++out->hits; }
  void tie() noexcept { ++out->ties; }
  void tie_without_arithmetic() noexcept { ++out->ties_without_arithmetic; }
  void comparison(Stage s) noexcept { ++out->comparisons[static_cast<std::size_t>(s)]; }
};

// One candidate's relation and, for a hit, its t = RN(num/den), each certified (triangle/ray_triangle_cascade.hpp):
// the fast path's relation (stage 1; a miss decided there costs nothing more), then for a hit the fast path's
// rounding of t (stage 2). What the fast paths leave open goes to the full cascade once, which classifies and
// rounds t in one pass (the stages it computes are shared). Valid input: the mesh was validated when prepared,
// the ray by the caller; the default floating-point environment is installed by the caller for the whole walk.
struct Candidate {
  TriangleRelation relation;
  TriangleLocation location;
  double t;  // RN(num/den) for a hit; NaN otherwise
  Stage stage;
};

Candidate classify(const Ray& ray, const Triangle& tri, TriangleRule rule) {
  const TriangleOptions t_only{.rule = rule, .t = true, .barycentric = false};
  if (const auto c = detail::fast_triangle_relation(ray, tri, rule)) [[likely]] {
    const TriangleClassification& r = c->classification;
    if (r.relation != TriangleRelation::hit) return {r.relation, r.location, not_a_number, c->stage};
    if (const auto x = detail::fast_triangle_intersection(ray, tri, t_only)) [[likely]]
      return {r.relation, r.location, x->intersection.t, c->stage};
  }
  const TracedTriangleIntersection x = detail::triangle_intersection_cascade(ray, tri, t_only);
  return {x.intersection.relation, x.intersection.location, x.intersection.t, x.relation_stage};
}

// The walk, in the default floating-point environment, for a valid ray.
template <class Tracer>
std::optional<MeshHit> nearest_in_default_environment(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule,
                                                      Tracer tracer) {
  const MeshBvh& bvh = mesh.bvh();
  if (bvh.nodes().empty()) return std::nullopt;
  detail::BvhWalk walk;
  mesh_detail::start_walk(walk, bvh, ray, 0, inf);
  const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
  const std::span<const Triangle> triangles = mesh.leaf_triangles();
  bool found = false;
  std::uint32_t best = 0, best_position = 0;
  double best_t = inf, bound = inf;
  BvhLeaf leaf;
  while (next_leaf(walk, bound, leaf)) {
    for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
      const Triangle& tri = triangles[leaf.position + n];
      const Candidate c = classify(ray, tri, rule);
      tracer.candidate(c.stage);
      if (c.relation != TriangleRelation::hit) continue;
      tracer.hit();
      const std::uint32_t k = leaf.triangles[n];
      const double t = c.t;
      if (found) {
        if (t > best_t) continue;
        if (t == best_t) {
          tracer.tie();
          const int order = detail::exact::compare_triangle_t(ray, tri, triangles[best_position]);
          tracer.comparison(Stage::exact);
          if (order > 0 || (order == 0 && k > best)) continue;
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
  const TriangleOptions all{.rule = rule};
  const Triangle& winner = triangles[best_position];
  const auto x = detail::fast_triangle_intersection(ray, winner, all);
  return MeshHit{best, x ? x->intersection : detail::triangle_intersection_cascade(ray, winner, all).intersection};
}

}  // namespace

std::optional<MeshHit> nearest_hit(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return nearest_in_default_environment(ray, mesh, rule, NoTrace{}); });
}

TracedMeshHit nearest_hit_traced(const Ray& ray, const PreparedMesh& mesh, TriangleRule rule) {
  throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] {
    TracedMeshHit traced;
    traced.hit = nearest_in_default_environment(ray, mesh, rule, Trace{&traced});
    return traced;
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
