// The open segment from p to q against one triangle (docs/contract.md §8), certified, without a rounded direction.
//
// The segment is the line from p along d = q − p, 0 < t < 1. With S(x) = (x − a)·N, N = (b − a) × (c − a), the §6
// values of that line are, exactly,
//
//     num = (a − p)·N = −S(p),    den = d·N = S(q) − S(p),    π(u, v) = d·((u − p) × (v − p)) = det(q − p, u − p, v − p),
//
// so t = num/den = S(p)/(S(p) − S(q)) lies in (0, 1) exactly when S(p) and S(q) are nonzero with opposite signs
// (S(p) = 0: t = 0; S(q) = 0: t = 1; one sign: t < 0, t > 1, or den = 0 — parallel, coplanar or degenerate,
// which never count). Then den and num both have S(q)'s sign, and every decision is a sign of a 3×3 determinant
// of differences of the doubles given — orient3d (mesh_detail::orient3d_sign: Shewchuk's filter, exact
// expansions, rationals):
//
//     S(x) = det(x − a, b − a, c − a) = orient3d_sign(a, x, b, c),    π(u, v) = orient3d_sign(p, q, u, v).
//
// A π that is exactly 0 takes, under the owned rule, the sign of the first nonzero component of the tie-break
// vector d × (v − u) with the exact d = q − p: degree-2 polynomials (q_i − p_i)(v_j − u_j) − (q_j − p_j)(v_i − u_i),
// ray_triangle_formula.hpp's edge_tie_break with d as differences, decided by exact expansions
// (ray_triangle_stages.hpp, edge_tie_break_signs_by_expansion) and, when one is not exact (an underflow or
// overflow), by rationals (exact::segment_tie_break_signs). They are asked only for a π that is exactly 0 (a
// segment through an edge or vertex), so no binary64 filter precedes them. The decision from the signs is §6's
// own (ray_triangle_formula.hpp's classify_triangle), so the segment and the ray share one rule.
//
// Certified by:
//   proofs/triangle/SegmentSigns.v, `segment_num_is_side`, `segment_den_is_difference`, `segment_t_in_open_unit`;
//   proofs/triangle/SegmentSigns.v, `segment_crossing_signs`, `segment_plane_test_correct`;
//   proofs/triangle/SegmentSigns.v, `segment_side_is_orient3d`, `segment_pi_is_orient3d`, `orient3d_is_exact`;
//   (the identities above, and that each orient3d_sign call's argument order gives S(p), S(q) and the π);
//   proofs/orient/OrientFilter.v, `orient3d_filter_sound` (the filter of each sign).
#pragma once

#include "core/expansion_value.hpp"
#include "occlusion/exact_occlusion.hpp"
#include "orient/orient_predicates.hpp"
#include "triangle/ray_triangle_formula.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <raykernel/triangle.hpp>

#include <array>
#include <cstddef>

namespace raykernel::detail {

// Whether triangle `t` meets the open segment from p to q under `rule` (valid input: finite, p ≠ q).
[[nodiscard]] inline bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Triangle& t, TriangleRule rule) {
  const int sp = mesh_detail::orient3d_sign(t.a, p, t.b, t.c);
  if (sp == 0) return false;
  const int sq = mesh_detail::orient3d_sign(t.a, q, t.b, t.c);
  if (sq != -sp) return false;
  // den and num have S(q)'s sign (den = S(q) − S(p), num = −S(p)).
  auto edge = [&](int k) -> std::array<const Vec3*, 2> {
    return k == 0 ? std::array{&t.b, &t.c} : (k == 1 ? std::array{&t.c, &t.a} : std::array{&t.a, &t.b});
  };
  const TriangleClassification c = classify_triangle(
      rule, [&] { return sq; },
      [&](int k) {
        const auto [u, v] = edge(k);
        return mesh_detail::orient3d_sign(p, q, *u, *v);
      },
      [&](int k) {
        const auto [u, v] = edge(k);
        const auto d = difference_leaves<ExpansionValue<2>>(p, q, expansion_difference);  // q − p, exactly
        if (const auto s = edge_tie_break_signs_by_expansion(d, *u, *v)) return *s;
        return exact::segment_tie_break_signs(p, q, *u, *v);
      },
      [&] { return sq; }, [] { return false; });
  return c.relation == TriangleRelation::hit;
}

}  // namespace raykernel::detail
