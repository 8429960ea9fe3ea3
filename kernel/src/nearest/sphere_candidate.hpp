// The sphere kind of the nearest-hit module (nearest/nearest_candidates.hpp): a sphere with a root in the ray's
// interval, with the root that is its hit (docs/contract.md §8 and §10: the smallest root in the interval,
// [0, +inf] by default; sphere/ray_sphere_cascade.hpp, sphere_hit_in_interval) and that root correctly rounded by
// the certified ray–sphere cascade, which decides the relation and rounds both roots with its own certificates.
//
// Its t is U ∓ √V, a root and not a quotient, so it is not ordered by the quotient stages. It is ordered by the
// roundings, then exactly:
//   - RN is monotone, so RN(t_a) < RN(t_b) implies t_a < t_b: two candidates whose correctly rounded t differ are
//     ordered as their roundings (proofs/core/RoundOrder.v, `rn_strict_order`). The other kinds' round_t() is
//     RN(t) (their own certified rounding, then kept for the answer).
//   - Equal roundings (a near tie within half an ulp, or an exact tie) go to the exact stage: the sign of
//     U ∓ √V − N/D or of (U_a ∓ √V_a) − (U_b ∓ √V_b) in rationals (nearest/exact_nearest.hpp).
#pragma once

#include "nearest/exact_nearest.hpp"
#include "nearest/nearest_candidates.hpp"
#include "sphere/ray_sphere_cascade.hpp"

#include <raykernel/nearest_scene.hpp>
#include <raykernel/sphere.hpp>

#include <cstddef>
#include <optional>

namespace raykernel::detail {

struct SphereCandidate {
  static constexpr SurfaceKind kind = SurfaceKind::sphere;

  // Classifies sphere k; true when a root lies in `interval` (then this is its candidate, the smallest such root).
  bool classify(const Ray& ray, const Sphere& s, std::size_t k, const RayInterval& interval) noexcept {
    const TracedSphereIntersection traced = sphere_intersection_cascade(ray, s);
    relation_stage = traced.relation_stage;
    const std::optional<SphereRootHit> hit = sphere_hit_in_interval(ray, s, traced.intersection, interval);
    if (!hit) return false;
    index = k;
    sphere = &s;
    t_stage = traced.rounding_stage;
    root = traced.intersection.relation == SphereRelation::tangent ? 0 : hit->root;
    t = hit->t;
    return true;
  }

  // RN(t), rounded by the cascade with the relation.
  [[nodiscard]] double round_t() const noexcept { return t; }

  std::size_t index = 0;
  const Sphere* sphere = nullptr;
  int root = 0;  // the hit: −1 the smaller root t1, +1 the larger t2, 0 the tangent root t0
  double t = 0;  // RN of the hit's exact t
  Stage relation_stage = Stage::filter;
  Stage t_stage = Stage::filter;
};

// sign(t_a − t_b) of two candidates, one a sphere's at least: from their correctly rounded t (rn_strict_order),
// or, when the roundings are equal, in rationals (exact_order overloads: nearest/nearest_search.hpp across kinds,
// below for two spheres).
template <class A, class B>
[[nodiscard]] inline DistanceOrder compare_by_rounding(const Ray& ray, A& a, B& b) {
  const double ta = a.round_t(), tb = b.round_t();
  if (ta < tb) return DistanceOrder{-1, Stage::filter};
  if (ta > tb) return DistanceOrder{+1, Stage::filter};
  return DistanceOrder{exact_order(ray, a, b), Stage::exact};
}

[[nodiscard]] inline int exact_order(const Ray& ray, const SphereCandidate& a, const SphereCandidate& b) {
  return exact::compare_sphere_sphere_t(ray, *a.sphere, a.root, *b.sphere, b.root);
}

template <class B>
[[nodiscard]] inline DistanceOrder compare_candidates(const Ray& ray, SphereCandidate& a, B& b) {
  return compare_by_rounding(ray, a, b);
}
template <class A>
[[nodiscard]] inline DistanceOrder compare_candidates(const Ray& ray, A& a, SphereCandidate& b) {
  return compare_by_rounding(ray, a, b);
}
[[nodiscard]] inline DistanceOrder compare_candidates(const Ray& ray, SphereCandidate& a, SphereCandidate& b) {
  return compare_by_rounding(ray, a, b);
}

}  // namespace raykernel::detail
