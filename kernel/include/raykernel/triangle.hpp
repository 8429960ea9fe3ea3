// raykernel/triangle.hpp: exact ray–triangle intersection (docs/contract.md §6), watertight by construction.
//
// For a ray (origin o, direction d) and a triangle (a, b, c), every answer is exact for the doubles given.
// Over the reals, with e_v = v − o and π(p, q) = d·((p − o) × (q − o)) for a directed edge p → q:
//
//     πa = π(b, c),  πb = π(c, a),  πc = π(a, b),   den = πa + πb + πc = d·N,   N = (b − a) × (c − a),
//     num = (a − o)·N,   t = num/den,   barycentric coordinates (πa, πb, πc)/den.
//
// The line of the ray crosses the triangle's plane when den ≠ 0; the signs of the three π against den's say
// where (inside, on an edge, at a vertex, outside). Two rules turn that into a relation:
//   - closed: the triangle with its boundary (a ray through a shared edge hits both triangles);
//   - owned (the default): a π that is exactly 0 takes the sign of the first nonzero x, y, z component of
//     d × (q − p), the limit of moving the origin by (ε, ε², ε³). On a closed, consistently oriented mesh
//     whose shared vertices are the same doubles, every ray through an edge or a vertex is counted by exactly
//     one of the triangles around it (two or none at a silhouette), so the owned hits never leak and never
//     double-count.
// t and each barycentric coordinate are the exact rationals rounded to nearest, ties to even (as t is for a
// plane, docs/contract.md §1).
//
// `intersect` answers through a certified cascade (a binary64 filter, double-double enclosures, exact
// expansions, exact rationals); `intersect_exact` uses exact rationals only (the reference);
// `intersect_naive` is Möller–Trumbore in plain doubles (the baseline, without guarantees); `relation`
// decides the relation, location and owned flag without rounding anything.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/interval.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace raykernel {

// The triangle with vertices a, b, c (docs/contract.md §6). Its orientation is the order of the vertices:
// the normal N = (b − a) × (c − a). Degenerate triangles (collinear or repeated vertices) are valid input.
struct Triangle {
  Vec3 a, b, c;
};


// Which points of the triangle count as a hit (docs/contract.md §6).
enum class TriangleRule : std::uint8_t {
  owned,   // watertight tie-breaking: each edge and vertex belongs to exactly one triangle of a closed mesh
  closed,  // the triangle with its boundary
};

enum class TriangleRelation : std::uint8_t {
  hit,         // the ray passes through the triangle under the rule, at t ≥ 0 (t = 0: origin on it)
  behind,      // the line passes through the triangle under the rule, at t < 0
  miss,        // the line crosses the plane (den ≠ 0) outside the triangle under the rule
  degenerate,  // N = 0: collinear or repeated vertices (never a hit)
  parallel,    // N ≠ 0, den = 0, num ≠ 0: the line never meets the plane
  coplanar,    // N ≠ 0, den = 0, num = 0: the line lies in the plane (never a hit, even where it touches)
};

// Where the line meets the plane, from the signs of πa, πb, πc against den's (den ≠ 0).
enum class TriangleLocation : std::uint8_t {
  inside,    // all three π nonzero with den's sign
  edge_ab,   // πc = 0, πa and πb with den's sign
  edge_bc,   // πa = 0, πb and πc with den's sign
  edge_ca,   // πb = 0, πc and πa with den's sign
  vertex_a,  // πb = πc = 0
  vertex_b,  // πc = πa = 0
  vertex_c,  // πa = πb = 0
  outside,   // some π with the sign opposite to den's
  none,      // den = 0: the line does not cross the plane (degenerate, parallel, coplanar)
};

// What to compute. t and the barycentric coordinates are rounded only when asked for; what is not asked for
// is NaN.
struct TriangleOptions {
  TriangleRule rule = TriangleRule::owned;
  bool t = true;            // RN(num/den)
  bool barycentric = true;  // RN(πa/den), RN(πb/den), RN(πc/den)
};

// The relation-only answer: no t, no rounding.
struct TriangleClassification {
  TriangleRelation relation;  // under the rule asked for
  TriangleLocation location;  // none unless den ≠ 0 (relation hit, behind or miss)
  bool owned;                 // the owned rule lets the line through (false unless den ≠ 0)
};

// Barycentric coordinates (πa, πb, πc)/den of the point where the ray's line crosses the triangle's plane:
// the weights of the vertices a, b, c (they sum to 1 exactly; each is rounded on its own). Named as Python's
// raykernel.Barycentric(a, b, c); indexable as [0], [1], [2] in that order.
template <class T>
struct BarycentricOf {
  T a, b, c;
  [[nodiscard]] const T& operator[](std::size_t k) const noexcept { return k == 0 ? a : k == 1 ? b : c; }
  [[nodiscard]] T& operator[](std::size_t k) noexcept { return k == 0 ? a : k == 1 ? b : c; }
  friend bool operator==(const BarycentricOf&, const BarycentricOf&) = default;
};
using Barycentric = BarycentricOf<double>;

struct TriangleIntersection {
  TriangleRelation relation;  // under the rule asked for
  TriangleLocation location;  // none unless den ≠ 0
  bool owned;                 // the owned rule lets the line through (false unless den ≠ 0)
  double t;                   // RN(num/den) (an exact 0 is +0; a nonzero t rounding to 0 keeps its sign); NaN when
                              // den = 0 or not asked for
  Barycentric barycentric;   // RN(πa/den), RN(πb/den), RN(πc/den), each rounded on its own; NaN when den = 0
                              // or not asked for
};

// The reason `ray`/`triangle` are invalid input (a NaN or infinite component, a zero direction), or nothing.
// A degenerate triangle is valid input.
[[nodiscard]] std::optional<std::string> validate(const Ray& ray, const Triangle& triangle);

// The certified answer of docs/contract.md §6, from the cheapest stage whose certified error bound decides it.
// Thread-safe; answers through the exact stage when the floating-point environment is not the default one.
// Throws invalid_input.
[[nodiscard]] TriangleIntersection intersect(const Ray& ray, const Triangle& triangle,
                                             const TriangleOptions& options = {});

// The relation, location and owned flag alone (certified, nothing rounded): CGAL's do_intersect counterpart.
// Throws invalid_input.
[[nodiscard]] TriangleClassification relation(const Ray& ray, const Triangle& triangle,
                                              TriangleRule rule = TriangleRule::owned);

// The reference: exact rationals (GMP) for every value, MPFR for the roundings. Slow and obviously right.
// Throws invalid_input.
[[nodiscard]] TriangleIntersection intersect_exact(const Ray& ray, const Triangle& triangle,
                                                   const TriangleOptions& options = {});

// docs/contract.md §8 on one triangle: the intersection (as `intersect`) when the ray passes through the triangle
// under options.rule at an exact t in `interval` ([t_min, t_max], closed; the exact t compared with the doubles,
// never a rounded t); nothing when it does not (a miss, behind, or t outside the interval). Throws invalid_input
// (the ray, or the interval naming the bound).
[[nodiscard]] std::optional<TriangleIntersection> intersect(const Ray& ray, const RayInterval& interval,
                                                            const Triangle& triangle, const TriangleOptions& options = {});
// The same in exact rationals alone (the reference).
[[nodiscard]] std::optional<TriangleIntersection> intersect_exact(const Ray& ray, const RayInterval& interval,
                                                                  const Triangle& triangle,
                                                                  const TriangleOptions& options = {});

// Möller–Trumbore (1997) in plain binary64: e1 = b − a, e2 = c − a, P = d × e2, det = e1·P, T = o − a,
// u = T·P/det, Q = T × e1, v = d·Q/det, t = e2·Q/det, barycentric (1 − u − v, u, v). Its own closed test
// (u ≥ 0, v ≥ 0, u + v ≤ 1) decides hit, behind or miss; the location is read off the computed u, v, w
// compared with 0; degenerate, parallel and coplanar come from e1 × e2 == 0, det == 0 and T·(e1 × e2) == 0 in
// doubles. No validation, no guarantee, no owned rule (`owned` is its own test): the baseline users compare.
[[nodiscard]] TriangleIntersection intersect_naive(const Ray& ray, const Triangle& triangle) noexcept;

// `intersect` plus the stages that decided: the relation (signs of den, the three π, num and, when a π or den
// is exactly 0, the tie-break and degeneracy signs) and the roundings asked for (the slowest of them;
// relation_stage when nothing needed rounding).
struct TracedTriangleIntersection {
  TriangleIntersection intersection;
  Stage relation_stage;
  Stage rounding_stage;
};
[[nodiscard]] TracedTriangleIntersection intersect_traced(const Ray& ray, const Triangle& triangle,
                                                          const TriangleOptions& options = {});

// `intersect_exact` plus the exact values it decided from, in lowest terms: den, num, πa, πb, πc, and when
// den ≠ 0 the exact t and barycentric coordinates.
struct ExactTriangleIntersection {
  TriangleIntersection intersection;
  Rational den, num, pi_a, pi_b, pi_c;
  std::optional<Rational> t;
  std::optional<BarycentricOf<Rational>> barycentric;
};
[[nodiscard]] ExactTriangleIntersection intersect_exact_rational(const Ray& ray, const Triangle& triangle,
                                                                 TriangleRule rule = TriangleRule::owned);

[[nodiscard]] std::string_view to_string(TriangleRule rule) noexcept;          // "owned", "closed"
[[nodiscard]] std::string_view to_string(TriangleRelation relation) noexcept;  // "hit", ..., "coplanar"
[[nodiscard]] std::string_view to_string(TriangleLocation location) noexcept;  // "inside", "edge-ab", ..., "none"

}  // namespace raykernel
