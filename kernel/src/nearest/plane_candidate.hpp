// The plane kind of the nearest-hit module (nearest/nearest_candidates.hpp): a plane whose relation to the ray is
// hit, with the stage-1 values its relation was decided from (computed by nearest_hit's scalar loop or its screen,
// nearest/nearest_screen.hpp: the same bits) and the rest of its cascade (plane/ray_plane_cascade.hpp), built
// from those values the first time a comparison or the rounding needs a later stage.
//   stage 1: |num − value| ≤ radius, |den − value| ≤ radius by filter_enclosure: proofs/plane/PlaneFilter.v,
//            `num_filter_encloses`, `den_filter_encloses`
//   stage 2, 3 and t: RayPlaneCascade (its own certificates), t by certified_quotient.
#pragma once

#include "core/dot3_filter.hpp"
#include "core/quotient_rounding.hpp"
#include "core/sign.hpp"
#include "nearest/compare_quotients.hpp"
#include "plane/exact_plane.hpp"
#include "plane/exact_plane_compare.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/ray_plane_stages.hpp"

#include <raykernel/nearest_scene.hpp>
#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>

namespace raykernel::detail {

struct HitCandidate {
  static constexpr SurfaceKind kind = SurfaceKind::plane;

  HitCandidate(std::size_t plane_index, const Ray& ray, const Plane& plane, const Dot3Rounded& den_stage1,
               const Dot3Rounded& num_stage1) noexcept
      : index(plane_index), ray(&ray), plane(&plane), den(den_stage1), num(num_stage1) {}

  // The query's terms (plane/ray_plane_stages.hpp) from the kept stage-1 values: what ray_plane_terms would
  // compute (the differences are recomputed, the dot products are the ones kept).
  [[nodiscard]] [[gnu::always_inline]] RayPlaneTerms terms() const noexcept {
    RayPlaneTerms q;
    const double o[3] = {ray->origin.x, ray->origin.y, ray->origin.z};
    const double d[3] = {ray->direction.x, ray->direction.y, ray->direction.z};
    const double p[3] = {plane->point.x, plane->point.y, plane->point.z};
    const double n[3] = {plane->normal.x, plane->normal.y, plane->normal.z};
    for (int i = 0; i < 3; ++i) {
      q.o[i] = o[i], q.d[i] = d[i], q.p[i] = p[i], q.n[i] = n[i];
      q.diff[i] = p[i] - o[i];  // as ray_plane_terms: the stage-1 values below were computed from it
    }
    q.den = den;
    q.num = num;
    return q;
  }

  // The cascade of this plane, from the kept stage-1 values (built once, on the rare comparisons the filter
  // cannot decide, and for the rounding of t when stage 2's first level cannot round it).
  [[nodiscard]] RayPlaneCascade& cascade() noexcept {
    if (!full) full.emplace(*ray, *plane, terms());
    return *full;
  }

  [[gnu::always_inline]] [[nodiscard]] RoundedEnclosure num_filter() const noexcept {
    return filter_enclosure(num, bounds::filter_num_relative);
  }
  [[gnu::always_inline]] [[nodiscard]] RoundedEnclosure den_filter() const noexcept {
    return filter_enclosure(den, bounds::filter_den_relative);
  }
  [[nodiscard]] const Enclosure& num_compensated() noexcept { return cascade().num_compensated(); }
  [[nodiscard]] const Enclosure& den_compensated() noexcept { return cascade().den_compensated(); }
  [[nodiscard]] const ExactExpansions& expansions() noexcept { return cascade().expansions(); }

  // The signs of num and den, hence the relation: stage 1's when its filter certified both (den_filter, num_filter:
  // dot3_filter_lanes of the kept values, which never certifies a zero), else the cascade's, with the stage that
  // decided them — the one classification of a plane, for nearest_hit's search and the single-plane queries.
  [[gnu::always_inline]] Relation decide_signs(std::int64_t den_filter, std::int64_t num_filter) noexcept {
    if ((den_filter != uncertain_lane) & (num_filter != uncertain_lane)) [[likely]] {
      num_sign = static_cast<Sign>(num_filter);
      den_sign = static_cast<Sign>(den_filter);
    } else {
      const CertifiedSigns signs = certified_signs(cascade());
      num_sign = signs.num;
      den_sign = signs.den;
      relation_stage = signs.stage;
    }
    return relation_from_signs(static_cast<int>(num_sign), static_cast<int>(den_sign));
  }

  // RN(t), rounded the first time it is asked for: +0 when num = 0 exactly (decided with the relation), the
  // exact stage when the relation needed it (extreme exponents), else certified_quotient.
  // certified_quotient's first step, round_quotient on stage 2's first level, is taken here from the kept terms
  // without building the cascade (the same enclosures, the same answer); when it is not certain, the cascade built
  // for the rest keeps it instead of repeating it.
  [[gnu::always_inline]] double round_t() noexcept {
    if (!rounded) {
      rounded = true;
      if (num_sign == Sign::zero) {
        t = 0.0;
        t_stage = relation_stage;
        return t;
      }
      if (relation_stage != Stage::exact && !full) {
        const RayPlaneTerms q = terms();
        const QuotientRounding r = round_quotient(detail::num_compensated(q), prepare_divisor(detail::den_compensated(q)));
        if (r.certain) {
          t = r.t;
          t_stage = Stage::compensated;
          return t;
        }
        full.emplace(*ray, *plane, q);
        full->keep_compensated_rounding(r);
      }
      round_rest();
    }
    return t;
  }

  // The rest of the rounding: the exact stage when the relation needed it (extreme exponents), else
  // certified_quotient.
  void round_rest() noexcept {
    if (relation_stage == Stage::exact) {
      t = exact::intersect(*ray, *plane).t;
      t_stage = Stage::exact;
    } else {
      const auto [value, stage] = certified_quotient(cascade());
      t = value;
      t_stage = stage;
    }
  }

  std::size_t index;
  const Ray* ray;
  const Plane* plane;
  Dot3Rounded den, num;  // stage 1
  Sign num_sign = Sign::uncertain;
  Sign den_sign = Sign::uncertain;
  Stage relation_stage = Stage::filter;  // the stage that certified the two signs
  std::optional<RayPlaneCascade> full;
  bool rounded = false;
  double t = 0;
  Stage t_stage = Stage::filter;
};
using PlaneCandidate = HitCandidate;

// sign(t_a − t_b) of two planes in rationals: sign(Δ)·sign(den_a)·sign(den_b).
[[nodiscard]] inline int exact_order(const Ray& ray, const HitCandidate& a, const HitCandidate& b) {
  const int orientation = a.den_sign == b.den_sign ? 1 : -1;
  return orientation * exact::compare_quotients(ray, *a.plane, *b.plane);
}

}  // namespace raykernel::detail
