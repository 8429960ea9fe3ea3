// The triangle kind of the nearest-hit module (nearest/nearest_candidates.hpp): a triangle of a mesh whose
// relation to the ray is hit, with what its relation was decided from and the stages of its t = num/den, each
// computed once (docs/contract.md §6; den in the short form d·((b − a) × (c − a)), ray_triangle_stages.hpp):
//
//   relation  fast_triangle_relation (stage 1 of the three π and den in lanes, num for a line through the
//             triangle), which also hands over the stage-1 values of num and den; what it leaves open goes to
//             triangle_relation_cascade once (a triangle with two equal vertices is degenerate without
//             arithmetic: N = 0)
//   stage 1   those values as enclosures (num; den as π(b, c) with a in the origin's place):
//             proofs/triangle/TriangleFilter.v, `det3_filter_encloses` (the instances num_filter_encloses, pi_filter_encloses)
//   stage 2   triangle_quotient_compensated:
//             proofs/triangle/TriangleCompensated.v, `num_compensated_encloses`, `pi_compensated_encloses`
//   stage 3   value_expansion of num and den:
//             proofs/triangle/TriangleStage3Twins.v, `value_ev_exact`
//   t         round_quotient on stage 2, then on stage 3's tail enclosures:
//             proofs/plane/QuotientRounding.v, `round_quotient_sound`
//             proofs/plane/PlaneCompensated.v, `tail_sum_enclosure`
//             then at the rounding boundaries in expansions (core/quotient_boundary.hpp), then exactly
//             (exact::round_triangle_quotients)
//
// The storage of stages 2 and 3 is left uninitialized until used (a search keeps two candidates per kind and must
// not clear them per ray), and stage 3 is kept in short form: the candidate stays small.
#pragma once

#include "core/escalation.hpp"
#include "core/expansion.hpp"
#include "core/expansion_value.hpp"
#include "core/quotient_rounding.hpp"
#include "core/sign.hpp"
#include "mesh/exact_mesh.hpp"
#include "nearest/compare_quotients.hpp"
#include "nearest/exact_nearest.hpp"
#include "core/quotient_boundary.hpp"
#include "triangle/exact_triangle.hpp"
#include "triangle/ray_triangle_cascade.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <raykernel/nearest_scene.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <cstdint>

namespace raykernel::detail {

[[nodiscard]] inline bool same_point(const Vec3& p, const Vec3& q) noexcept {
  return p.x == q.x && p.y == q.y && p.z == q.z;
}
[[nodiscard]] inline bool is_vertex_of(const Vec3& p, const Triangle& t) noexcept {
  return same_point(p, t.a) || same_point(p, t.b) || same_point(p, t.c);
}

// The point where the line crosses a hit triangle's plane, when its location names it by vertices: the vertex
// (location vertex_*) or the two endpoints of the edge it lies on (edge_*). From the barycentric form
// X = (πa·a + πb·b + πc·c)/den (docs/contract.md §6): vertex_a has πb = πc = 0, so X = a; edge_ab has πc = 0,
// so X = (πa·a + πb·b)/den with πa + πb = den, a point of the line through a and b; and so on.
struct CrossingSite {
  const Vec3* p = nullptr;  // the vertex, or the edge's first endpoint; null for inside
  const Vec3* q = nullptr;  // the edge's second endpoint; null for a vertex
};
[[nodiscard]] inline CrossingSite crossing_site(const Triangle& t, TriangleLocation location) noexcept {
  switch (location) {
    case TriangleLocation::vertex_a: return {&t.a, nullptr};
    case TriangleLocation::vertex_b: return {&t.b, nullptr};
    case TriangleLocation::vertex_c: return {&t.c, nullptr};
    case TriangleLocation::edge_ab: return {&t.a, &t.b};
    case TriangleLocation::edge_bc: return {&t.b, &t.c};
    case TriangleLocation::edge_ca: return {&t.c, &t.a};
    default: return {};
  }
}

// Whether two triangles the ray hits (so den ≠ 0 for both: each is non-degenerate and the line crosses its plane
// at exactly one point) certainly have the same exact t, by comparing their vertices' doubles only. Each case
// shows that the two crossing points are one point X of the line, whose parameter t is unique (d ≠ 0):
//   - s's three vertices are vertices of t (the same triangle in any vertex order, or reversed): they span s's
//     plane (s is non-degenerate) and lie on t's, so the planes are one;
//   - all six vertices have the same coordinate x_k = v on some axis k: each plane contains three
//     non-collinear points of {x_k = v}, so both are {x_k = v};
//   - both are crossed at a vertex, the same point (crossing_site);
//   - both are crossed inside an edge, with the same two endpoints: both crossing points lie on the line L
//     through them, which lies in both planes; the ray's line is not L (it would lie in a plane: den = 0), so it
//     meets L at one point at most — both crossing points are that point.
[[nodiscard]] inline bool same_t_by_vertices(const Triangle& s, TriangleLocation s_location, const Triangle& t,
                                             TriangleLocation t_location) noexcept {
  if (is_vertex_of(s.a, t) && is_vertex_of(s.b, t) && is_vertex_of(s.c, t)) return true;
  if (s.a.x == s.b.x && s.a.x == s.c.x && s.a.x == t.a.x && s.a.x == t.b.x && s.a.x == t.c.x) return true;
  if (s.a.y == s.b.y && s.a.y == s.c.y && s.a.y == t.a.y && s.a.y == t.b.y && s.a.y == t.c.y) return true;
  if (s.a.z == s.b.z && s.a.z == s.c.z && s.a.z == t.a.z && s.a.z == t.b.z && s.a.z == t.c.z) return true;
  const CrossingSite x = crossing_site(s, s_location), y = crossing_site(t, t_location);
  if (x.p == nullptr || y.p == nullptr || (x.q == nullptr) != (y.q == nullptr)) return false;
  if (x.q == nullptr) return same_point(*x.p, *y.p);
  return (same_point(*x.p, *y.p) && same_point(*x.q, *y.q)) || (same_point(*x.p, *y.q) && same_point(*x.q, *y.p));
}

// Whether triangle `t` has the relation, location and t of triangle `s` (whose location is given), from their
// vertices' doubles: the relation and t are functions of the exact inputs (docs/contract.md §6), so
//   - the same three points in the same order repeat all three;
//   - the same points in another order (each vertex of either is one of the other's; with a repeated point both
//     are degenerate) repeat the relation and t: a rotation renames the π's; a swap of two vertices negates den,
//     num, every π and every edge's tie-break vector d × (q − p) (its edge is reversed), which leaves each
//     comparison that decides the relation — a π's sign or owned sign against den's, num·den ≥ 0 — as it was;
//     and t = num/den is unchanged. The location names vertices (edge_ab, vertex_c, ...) except inside, outside
//     and none, which are the same for every order: reused only then.
[[nodiscard]] inline bool repeats(const Triangle& t, const Triangle& s, TriangleLocation s_location) noexcept {
  if (same_point(t.a, s.a) && same_point(t.b, s.b) && same_point(t.c, s.c)) return true;
  if (s_location != TriangleLocation::inside && s_location != TriangleLocation::outside &&
      s_location != TriangleLocation::none)
    return false;
  return is_vertex_of(t.a, s) && is_vertex_of(t.b, s) && is_vertex_of(t.c, s) && is_vertex_of(s.a, t) &&
         is_vertex_of(s.b, t) && is_vertex_of(s.c, t);
}

// The triangles of a BVH leaf (`count` of them from `first` in `triangles`) screened four at a time
// (triangle_screen) when a triangle of a group is first asked about: the ones the ray certainly misses, and the
// ones it certainly crosses inside (whose relation num's sign alone decides, TriangleCandidate::classify_screened);
// a lane past the leaf's end repeats the group's first triangle and is not read. The callers classify only the
// triangles not missed.
class LeafScreen {
 public:
  LeafScreen(const Ray& ray, std::span<const Triangle> triangles, std::size_t first, std::size_t count) noexcept
      : ray_(ray), triangles_(triangles), first_(first), count_(count) {}

  // Whether the leaf's n-th triangle is certainly missed.
  [[gnu::always_inline]] bool certainly_missed(std::size_t n) noexcept {
    if (n / 4 != group_) {
      group_ = n / 4;
      const std::size_t start = first_ + 4 * group_;
      const std::size_t lanes = count_ - 4 * group_ < 4 ? count_ - 4 * group_ : 4;
      const Triangle* t[4];
      for (std::size_t j = 0; j < 4; ++j) t[j] = &triangles_[start + (j < lanes ? j : 0)];
      triangle_screen(ray_, t, screen_);
      screen_.missed &= (1u << lanes) - 1;
      screen_.inside &= (1u << lanes) - 1;
    }
    return ((screen_.missed >> (n % 4)) & 1) != 0;
  }
  // Whether the ray certainly crosses the n-th triangle's interior (line through it); after certainly_missed(n).
  [[nodiscard]] bool certainly_inside(std::size_t n) const noexcept { return ((screen_.inside >> (n % 4)) & 1) != 0; }
  // Its den in stage 1 and den's sign, d's absolute term; for a triangle certainly_inside.
  [[nodiscard]] FilterTerm<double> den(std::size_t n) const noexcept { return lane(screen_.den, static_cast<int>(n % 4)); }
  [[nodiscard]] std::int64_t den_sign(std::size_t n) const noexcept { return screen_.den_sign[n % 4]; }
  [[nodiscard]] double absolute() const noexcept { return screen_.absolute; }

 private:
  const Ray& ray_;
  std::span<const Triangle> triangles_;
  std::size_t first_, count_;
  std::size_t group_ = SIZE_MAX;
  TriangleScreen screen_;
};

// Stage 3 of num and den for the comparisons: exact expansions of at most 16 components each (the range
// compare_quotients_expansion is proved for), or exact = false.
struct ShortQuotientExpansions {
  bool exact;
  Expansion<16> num, den;
};

class TriangleCandidate {
 public:
  static constexpr SurfaceKind kind = SurfaceKind::triangle;

  TriangleCandidate() noexcept {}  // NOLINT: filled by classify

  // Classifies `tri` (mesh index `mesh_index`, at `leaf_position` in the BVH's order) under `rule`; for a hit,
  // also the exact signs of num and den. Valid input: the mesh was validated when prepared, the ray by the
  // caller; the default floating-point environment is installed.
  [[gnu::always_inline]] void classify(const Ray& ray, const Triangle& tri, std::size_t mesh_index,
                                       std::uint32_t leaf_position, TriangleRule rule) noexcept {
    ray_ = &ray;
    source = triangle = &tri;
    index = mesh_index;
    position = leaf_position;
    has_stage2_ = has_expansions_ = rounded = false;
    if (const auto c = fast_triangle_relation(ray, tri, rule, stage1_)) [[likely]] {
      classification = c->classification;
      relation_stage = c->stage;
      if (classification.relation == TriangleRelation::hit) {  // den and num certain, nonzero, of one sign
        den_sign = num_sign = stage1_.den.v > 0 ? Sign::positive : Sign::negative;
      }
      return;
    }
    if (same_point(tri.a, tri.b) || same_point(tri.b, tri.c) || same_point(tri.c, tri.a)) {
      classification = {TriangleRelation::degenerate, TriangleLocation::none, false};
      relation_stage = Stage::filter;
      return;
    }
    classify_rare(rule);
  }

  // What classify sets for a triangle the leaf filter found certainly missed (LeafScreen): the
  // classification fast_triangle_relation would return, decided from the same stage-1 values.
  [[gnu::always_inline]] void set_certain_miss(const Ray& ray, const Triangle& tri, std::size_t mesh_index,
                                               std::uint32_t leaf_position) noexcept {
    ray_ = &ray;
    source = triangle = &tri;
    index = mesh_index;
    position = leaf_position;
    has_stage2_ = has_expansions_ = rounded = false;
    classification = {TriangleRelation::miss, TriangleLocation::outside, false};
    relation_stage = Stage::filter;
  }

  // classify for the n-th triangle of a leaf the screen did not find missed (certainly_missed(n) asked first):
  // for one it found inside (LeafScreen::certainly_inside: den and the three π certain, all of den's sign), the
  // classification and stage-1 values fast_triangle_relation would give, decided from the same values (den's
  // stage-1 value is the screen's lane) with num's stage-1 sign alone; classify itself for the others and when
  // num's sign is uncertain.
  [[gnu::always_inline]] void classify_screened(const Ray& ray, const Triangle& tri, std::size_t mesh_index,
                                              std::uint32_t leaf_position, TriangleRule rule,
                                              const LeafScreen& screen, std::size_t n) noexcept;

  // Another triangle with this one's vertices (repeats()): the same relation, location and t, so this
  // candidate's values stand for it; it takes over the identity (index, position, the triangle reported).
  [[gnu::always_inline]] void take_identity(const Triangle& tri, std::size_t mesh_index, std::uint32_t leaf_position) noexcept {
    triangle = &tri;
    index = mesh_index;
    position = leaf_position;
  }

  [[gnu::always_inline]] [[nodiscard]] RoundedEnclosure num_filter() const noexcept {
    return {stage1_.num.v, plus_absolute_term(bounds::triangle_filter_num_relative * stage1_.num.m, stage1_.absolute_e)};
  }
  [[gnu::always_inline]] [[nodiscard]] RoundedEnclosure den_filter() const noexcept {
    return {stage1_.den.v, plus_absolute_term(bounds::triangle_filter_pi_relative * stage1_.den.m, stage1_.absolute_d)};
  }
  [[gnu::always_inline]] [[nodiscard]] const Enclosure& num_compensated() noexcept { return stage2().num; }
  [[gnu::always_inline]] [[nodiscard]] const Enclosure& den_compensated() noexcept { return stage2().den; }
  [[nodiscard]] const ShortQuotientExpansions& expansions() noexcept {
    stage3();
    return short_;
  }

  // RN(t), rounded the first time it is asked for, and the stage that rounded it: +0 for num = 0 exactly,
  // round_quotient on stage 2, and beyond (round_triangle_t_beyond_stage2) only when that cannot decide.
  [[gnu::always_inline]] double round_t() noexcept {
    if (!rounded) {
      rounded = true;
      if (num_sign == Sign::zero) {  // t = 0 exactly: +0, decided with the relation
        t = 0.0;
        t_stage = relation_stage;
      } else {
        const QuotientRounding r = round_quotient(num_compensated(), prepare_divisor(den_compensated()));
        t = r.t;
        t_stage = Stage::compensated;
        if (!r.certain) [[unlikely]]
          round_triangle_t_beyond_stage2(*this, r.t);
      }
    }
    return t;
  }
  // Stage 3's roundings, the rounding boundaries, then the exact stage, from the candidate q of stage 2
  // (nearest/nearest_stages.cpp: multiversioned).
  friend void round_triangle_t_beyond_stage2(TriangleCandidate& c, double candidate) noexcept;

  // Identity: what the answer reports.
  std::size_t index = 0;
  std::uint32_t position = 0;  // in the BVH's triangle order (PreparedMesh::leaf_triangles)
  const Triangle* triangle = nullptr;
  // The triangle whose values the stages compute: `triangle`, or the one this candidate repeated.
  const Triangle* source = nullptr;

  TriangleClassification classification{};
  Stage relation_stage = Stage::filter;
  Sign num_sign = Sign::uncertain;  // for a hit: exact
  Sign den_sign = Sign::uncertain;

  bool rounded = false;
  double t = 0;
  Stage t_stage = Stage::filter;

 private:
  // The relation by the full cascade, then the exact signs of num and den of a hit by this candidate's own
  // stages (filter, compensated, expansion, rationals).
  [[gnu::noinline]] void classify_rare(TriangleRule rule) noexcept {
    const TracedTriangleClassification c = triangle_relation_cascade(*ray_, *source, rule);
    classification = c.classification;
    relation_stage = c.stage;
    if (classification.relation != TriangleRelation::hit) return;
    stage1_ = triangle_quotient_filter(*ray_, *source);
    // Each sign through this candidate's stages (core/escalation.hpp); the trace is not reported (relation_stage
    // is the relation's, and the comparisons trace their own stages).
    Escalation signs;
    const auto escalate = [&](bool is_num) {
      return signs.sign(SignStage{Stage::filter, [&] {
                          return static_cast<Sign>(is_num ? det3_filter_lanes(stage1_.num, bounds::triangle_filter_num_relative,
                                                                              stage1_.absolute_e)
                                                          : det3_filter_lanes(stage1_.den, bounds::triangle_filter_pi_relative,
                                                                              stage1_.absolute_d));
                        }},
                        SignStage{Stage::compensated,
                                  [&] { return enclosure_sign(is_num ? num_compensated() : den_compensated()); }},
                        SignStage{Stage::expansion, [&] {
                          stage3();
                          return is_num ? num3_sign_ : den3_sign_;
                        }});
    };
    Sign num = escalate(true);
    Sign den = escalate(false);
    if (!is_certain(num) || !is_certain(den)) {
      const exact::QuotientSigns s = exact::triangle_quotient_signs(*ray_, *source);
      num = static_cast<Sign>(s.num);
      den = static_cast<Sign>(s.den);
    }
    num_sign = num;
    den_sign = den;
  }

  [[gnu::always_inline]] const TriangleQuotientStage2& stage2() noexcept {
    if (!has_stage2_) stage2_ = triangle_quotient_compensated(*ray_, *source);
    has_stage2_ = true;
    return stage2_;
  }

  // Stage 3 of num and den, computed once and kept in short form (the full expansions live in this function's
  // frame only, so that a search's candidates stay small): the expansions of at most 16 components for the
  // comparisons and the rounding boundaries, their tail enclosures for round_quotient, their signs.
  [[gnu::noinline]] void stage3() noexcept {
    if (has_expansions_) return;
    const ExpansionValue<192> num = value_expansion(*ray_, *source, value_num);
    const ExpansionValue<192> den = value_expansion(*ray_, *source, value_den);
    short_.exact = num.exact && den.exact && num.e.size <= 16 && den.e.size <= 16;
    if (short_.exact) {
      for (std::size_t i = 0; i < num.e.size; ++i) short_.num.component[i] = num.e.component[i];
      short_.num.size = num.e.size;
      for (std::size_t i = 0; i < den.e.size; ++i) short_.den.component[i] = den.e.component[i];
      short_.den.size = den.e.size;
    }
    num3_tail_ = tail_enclosure(num);
    den3_tail_ = tail_enclosure(den);
    num3_sign_ = num.sign();
    den3_sign_ = den.sign();
    has_expansions_ = true;
  }

  // Stage 3's enclosure of a value: expansion_tail_enclosure of its exact expansion, when it is exact and has
  // at most bounds::tail_sum_max_terms components (the range tail_sum_enclosure is proved for).
  static std::optional<Enclosure> tail_enclosure(const ExpansionValue<192>& value) noexcept {
    if (!value.exact || value.e.size > bounds::tail_sum_max_terms) return std::nullopt;
    Expansion<bounds::tail_sum_max_terms> short_form{};
    for (std::size_t i = 0; i < value.e.size; ++i) short_form.component[i] = value.e.component[i];
    short_form.size = value.e.size;
    return expansion_tail_enclosure(short_form);
  }

  const Ray* ray_ = nullptr;
  TriangleQuotientStage1 stage1_;  // valid for a hit
  bool has_stage2_ = false, has_expansions_ = false;
  TriangleQuotientStage2 stage2_;
  ShortQuotientExpansions short_;
  std::optional<Enclosure> num3_tail_, den3_tail_;
  Sign num3_sign_ = Sign::uncertain, den3_sign_ = Sign::uncertain;
};

// TriangleCandidate::classify_screened (declared in the class, defined after LeafScreen's members).
[[gnu::always_inline]] inline void TriangleCandidate::classify_screened(const Ray& ray, const Triangle& tri,
                                                                     std::size_t mesh_index, std::uint32_t leaf_position,
                                                                     TriangleRule rule, const LeafScreen& screen,
                                                                     std::size_t n) noexcept {
  if (!screen.certainly_inside(n)) return classify(ray, tri, mesh_index, leaf_position, rule);
  const InsideRelation through = inside_relation(ray, tri, screen.den(n), screen.absolute());
  if (through.num_sign == uncertain_lane) [[unlikely]]
    return classify(ray, tri, mesh_index, leaf_position, rule);
  ray_ = &ray;
  source = triangle = &tri;
  index = mesh_index;
  position = leaf_position;
  has_stage2_ = has_expansions_ = rounded = false;
  stage1_ = through.values;
  classification = through.classification(screen.den_sign(n));
  relation_stage = Stage::filter;
  if (classification.relation == TriangleRelation::hit)  // den and num certain, nonzero, of one sign
    den_sign = num_sign = stage1_.den.v > 0 ? Sign::positive : Sign::negative;
}

// RN(πa/den), RN(πb/den), RN(πc/den) of a triangle the ray hits (the fast path, else the cascade).
[[nodiscard]] inline Barycentric triangle_barycentric(const Ray& ray, const Triangle& tri,
                                                                TriangleRule rule) noexcept {
  const TriangleOptions barycentric{.rule = rule, .t = false, .barycentric = true};
  if (const auto x = fast_triangle_intersection(ray, tri, barycentric)) [[likely]]
    return x->intersection.barycentric;
  return triangle_intersection_cascade(ray, tri, barycentric).intersection.barycentric;
}

// Two triangles with one plane or one crossing point (same_t_by_vertices) tie without arithmetic.
[[nodiscard]] inline bool same_t_without_arithmetic(const TriangleCandidate& a, const TriangleCandidate& b) noexcept {
  return same_t_by_vertices(*a.triangle, a.classification.location, *b.triangle, b.classification.location);
}

[[nodiscard]] inline int exact_order(const Ray& ray, const TriangleCandidate& a, const TriangleCandidate& b) {
  return exact::compare_triangle_t(ray, *a.source, *b.source);
}

}  // namespace raykernel::detail
