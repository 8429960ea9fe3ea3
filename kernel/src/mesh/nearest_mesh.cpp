// nearest_hit(ray, mesh) (docs/contract.md §7): the BVH walk, nearest leaf first, with the certified ray–triangle
// cascade on each candidate; the reference nearest_hit_exact in rationals; the Möller–Trumbore baseline.
//
// Why the answer is the brute-force one:
//   - Every triangle hit at an exact t ≤ the bound in force is in a returned leaf (bvh.hpp's guarantee).
//   - The bound passed to the walk is +inf until a hit is found, then nextup(RN(t_best)): RN moves a value by
//     at most half an ulp, so t_best < nextup(RN(t_best)); any triangle that could win (t ≤ t_best) is kept.
//   - Two hits are ordered by RN(t): RN is monotone, so RN(t1) < RN(t2) implies t1 < t2. When RN(t1) = RN(t2)
//     (a tie of the rounded t), the exact t are compared: equal without arithmetic when the vertices show that
//     both lines cross one plane or one point (same_t_by_vertices), else by the certified comparison of two
//     quotients num/den (compare_tied_t: double-double enclosures, exact expansions, then rationals); an exact tie
//     goes to the smaller index.
//   - A candidate with the previous one's vertices (in the same order, or in another one when the location names
//     no vertex) has the same relation and t, which are functions of the exact inputs (docs/contract.md §6):
//     they are reused (repeats).
//
// Cost: a tie used to cost a comparison in rationals (about 5 µs); 100,000 copies of one triangle cost
// 0.4 s per ray, a fan of 10^6 overlapping coplanar triangles seconds. A tie now costs nothing for copies (in any
// vertex order) and for triangles in one axis-aligned plane or crossed at one shared vertex or edge, and a
// stage-2 or stage-3 comparison otherwise; rationals only when those cannot decide (exact ties whose expansions
// exceed the proved length, or an underflow).
#include <raykernel/mesh_queries.hpp>

#include "nearest/compare_quotients.hpp"
#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "mesh/exact_mesh.hpp"
#include "core/fp_environment.hpp"
#include "mesh/bvh_walk.hpp"
#include "triangle/ray_triangle_cascade.hpp"
#include "triangle/ray_triangle_stages.hpp"
#include "core/validation.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace raykernel {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

void throw_if_invalid(const Ray& ray) {
  if (detail::is_valid(ray)) [[likely]]
    return;
  throw invalid_input(*validate(ray));
}

// Records what a traced query cost (TracedMeshHit); NoTrace compiles to nothing.
struct NoTrace {
  void candidate(Stage) noexcept {}
  void repeat() noexcept {}
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
  void repeat() noexcept {
    ++out->candidates;
    ++out->repeats;
  }
  void hit() noexcept { ++out->hits; }
  void tie() noexcept { ++out->ties; }
  void tie_without_arithmetic() noexcept { ++out->ties_without_arithmetic; }
  void comparison(Stage s) noexcept { ++out->comparisons[static_cast<std::size_t>(s)]; }
};

// One candidate's relation, certified (triangle/ray_triangle_cascade.hpp): the fast path's (stage 1), which
// decides most candidates, misses and hits alike; what it leaves open goes to the full cascade once, which for a
// hit rounds t in the same pass (the stages it computes are shared) — except a triangle with two equal vertices,
// whose normal N = (b − a) × (c − a) is exactly 0 (a factor is the zero vector): degenerate, never hit, no
// arithmetic (a fan of a polygon with repeated vertices has many). A hit's t = RN(num/den) is rounded only when
// the order needs it (hit_t): not for a hit certainly tied with the best one by its vertices. Valid input: the
// mesh was validated when prepared, the ray by the caller; the default floating-point environment is installed
// by the caller for the whole walk.
struct Candidate {
  TriangleRelation relation;
  TriangleLocation location;
  double t;  // RN(num/den) for a hit, once rounded; NaN before
  Stage stage;
};

bool same_point(const Vec3& p, const Vec3& q) noexcept { return p.x == q.x && p.y == q.y && p.z == q.z; }

Candidate classify(const Ray& ray, const Triangle& tri, TriangleRule rule) {
  if (const auto c = detail::fast_triangle_relation(ray, tri, rule)) [[likely]]
    return {c->classification.relation, c->classification.location, not_a_number, c->stage};
  if (same_point(tri.a, tri.b) || same_point(tri.b, tri.c) || same_point(tri.c, tri.a))
    return {TriangleRelation::degenerate, TriangleLocation::none, not_a_number, Stage::filter};
  const TracedTriangleIntersection x =
      detail::triangle_intersection_cascade(ray, tri, TriangleOptions{.rule = rule, .t = true, .barycentric = false});
  return {x.intersection.relation, x.intersection.location, x.intersection.t, x.relation_stage};
}

// RN(t) of a hit: the fast path's rounding (stage 2), else the full cascade's.
double hit_t(const Ray& ray, const Triangle& tri, TriangleRule rule) {
  const TriangleOptions t_only{.rule = rule, .t = true, .barycentric = false};
  if (const auto x = detail::fast_triangle_intersection(ray, tri, t_only)) [[likely]]
    return x->intersection.t;
  return detail::triangle_intersection_cascade(ray, tri, t_only).intersection.t;
}

// ---- Ties of the rounded t --------------------------------------------------------------------------------

// The point where the line crosses a hit triangle's plane, when its location names it by vertices: the vertex
// (location vertex_*) or the two endpoints of the edge it lies on (edge_*). From the barycentric form
// X = (πa·a + πb·b + πc·c)/den (docs/contract.md §6): vertex_a has πb = πc = 0, so X = a; edge_ab has πc = 0,
// so X = (πa·a + πb·b)/den with πa + πb = den, a point of the line through a and b; and so on.
struct CrossingSite {
  const Vec3* p = nullptr;  // the vertex, or the edge's first endpoint; null for inside
  const Vec3* q = nullptr;  // the edge's second endpoint; null for a vertex
};
CrossingSite crossing_site(const Triangle& t, TriangleLocation location) noexcept {
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

bool is_vertex_of(const Vec3& p, const Triangle& t) noexcept {
  return same_point(p, t.a) || same_point(p, t.b) || same_point(p, t.c);
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
bool same_t_by_vertices(const Triangle& s, TriangleLocation s_location, const Triangle& t,
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

// A hit's values for comparing its exact t = num/den with another hit's, each computed on first use: the stage-2
// enclosures of num and den (ray_triangle_stages.hpp), then their exact stage-3 expansions (den as
// d·((b − a) × (c − a)), the shorter form of the same value). A few kB, left uninitialized until used (no
// std::optional, which GCC clears whole on construction: once per ray).
class TiedHit {
 public:
  TiedHit() noexcept {}  // NOLINT: the values are filled on first use
  void reset(const Triangle* triangle) noexcept {
    triangle_ = triangle;
    has_compensated_ = has_num_ = has_den_ = false;
  }
  [[nodiscard]] const Triangle& triangle() const noexcept { return *triangle_; }
  [[nodiscard]] bool holds(const Triangle* triangle) const noexcept { return triangle_ == triangle; }
  [[gnu::always_inline]] const detail::TriangleCompensatedValues& compensated(const Ray& ray) noexcept {
    if (!has_compensated_) compensated_ = detail::triangle_compensated_values(ray, *triangle_);
    has_compensated_ = true;
    return compensated_;
  }
  const detail::ExpansionValue<192>& num(const Ray& ray) noexcept {
    if (!has_num_) num_ = detail::value_expansion(ray, *triangle_, detail::value_num);
    has_num_ = true;
    return num_;
  }
  const detail::ExpansionValue<192>& den(const Ray& ray) noexcept {
    if (!has_den_) den_ = detail::value_expansion(ray, *triangle_, detail::value_den);
    has_den_ = true;
    return den_;
  }

 private:
  const Triangle* triangle_ = nullptr;
  bool has_compensated_ = false, has_num_ = false, has_den_ = false;
  detail::TriangleCompensatedValues compensated_;
  detail::ExpansionValue<192> num_, den_;
};

// An exact expansion with at most 16 components (compare_quotients_expansion's proved range), or nothing.
constexpr std::size_t short_expansion_terms = 16;
std::optional<detail::Expansion<short_expansion_terms>> short_form(const detail::ExpansionValue<192>& v) noexcept {
  if (!v.exact || v.e.size > short_expansion_terms) return std::nullopt;
  detail::Expansion<short_expansion_terms> e;
  for (std::size_t i = 0; i < v.e.size; ++i) e.component[i] = v.e.component[i];
  e.size = v.e.size;
  return e;
}

struct TieOrder {
  int sign;  // of t_a − t_b
  Stage stage;
};

// The sign of t_a − t_b for two hits (den_a, den_b ≠ 0), certified, without rationals: sign(t_a − t_b) =
// sign(Δ)·sign(den_a)·sign(den_b), Δ = num_a·den_b − num_b·den_a (nearest/compare_quotients.hpp, the ray–plane
// nearest hit's comparison, on the triangles' num and den):
//   stage 2  compare_quotients_compensated on the stage-2 enclosures of num and den (proofs/triangle/TriangleCompensated.v,
//            `num_compensated_encloses`, `den_compensated_encloses`: the enclosures its theorem
//            `compare_quotients_compensated_enclosure` takes), its sign and den's by enclosure_sign;
//   stage 3  compare_quotients_expansion on the exact expansions (proofs/triangle/TriangleStage3Twins.v, `value_ev_exact`:
//            their exact sums are num and den; proofs/core/Expansions.v, `compare_quotients_expansion_sound`, for at
//            most 16 components each), den's sign by the checked expansion sign.
// Stage 1 (compare_quotients_filter on the stage-1 values) is not tried: it cannot decide a tie of the rounded t.
// Equal RN(t) put the exact t within an ulp of each other, |t_a − t_b| ≤ 2u·|t_a| (u = 2^-53), so
// |Δ| = |t_a − t_b|·|den_a·den_b| ≤ 2u·|num_a·den_b|; its bound exceeds that, since the stage-1 radii alone are at
// least 8u·m ≥ 8u·|value| for num and den (error_bounds.hpp, "Ray–triangle", stage 1) and enter it as
// |x_a|·f_b + e_a·|y_b| ≥ 16u·|num_a·den_b| (up to rounding). Nothing when neither stage decides (an exact tie
// with expansions longer than 16 components, or an underflow): the caller compares in rationals.
RAYKERNEL_MULTIVERSION
std::optional<TieOrder> compare_tied_t(const Ray& ray, TiedHit& a, TiedHit& b) noexcept {
  using detail::value_den;
  using detail::value_num;
  const detail::TriangleCompensatedValues& sa = a.compensated(ray);
  const detail::TriangleCompensatedValues& sb = b.compensated(ray);
  const detail::Enclosure da = sa.enclosure(value_den), db = sb.enclosure(value_den);
  const detail::Sign den_a = detail::enclosure_sign(da), den_b = detail::enclosure_sign(db);
  if (detail::is_certain(den_a) && detail::is_certain(den_b)) {
    const detail::Sign delta = detail::enclosure_sign(
        detail::compare_quotients_compensated(sa.enclosure(value_num), da, sb.enclosure(value_num), db));
    if (detail::is_certain(delta))
      return TieOrder{static_cast<int>(delta) * static_cast<int>(den_a) * static_cast<int>(den_b), Stage::compensated};
  }
  const auto na = short_form(a.num(ray)), nb = short_form(b.num(ray));
  if (!na || !nb) return std::nullopt;
  const auto xa = short_form(a.den(ray)), xb = short_form(b.den(ray));
  if (!xa || !xb) return std::nullopt;
  const detail::Sign sign_a = xa->sign(), sign_b = xb->sign();
  if (!detail::is_certain(sign_a) || !detail::is_certain(sign_b)) return std::nullopt;
  const detail::Sign delta = detail::compare_quotients_expansion(*na, *xa, *nb, *xb);
  if (!detail::is_certain(delta)) return std::nullopt;
  return TieOrder{static_cast<int>(delta) * static_cast<int>(sign_a) * static_cast<int>(sign_b), Stage::expansion};
}

// Whether candidate `t` has the relation, location and t of the previous candidate `s` (whose location is given),
// from their vertices' doubles: the relation and t are functions of the exact inputs (docs/contract.md §6), so
//   - the same three points in the same order repeat all three;
//   - the same points in another order (each vertex of either is one of the other's; with a repeated point both
//     are degenerate) repeat the relation and t: a rotation renames the π's; a swap of two vertices negates den,
//     num, every π and every edge's tie-break vector d × (q − p) (its edge is reversed), which leaves each
//     comparison that decides the relation — a π's sign or owned sign against den's, num·den ≥ 0 — as it was;
//     and t = num/den is unchanged. The location names vertices (edge_ab, vertex_c, ...) except inside, outside
//     and none, which are the same for every order: reused only then.
bool repeats(const Triangle& t, const Triangle& s, TriangleLocation s_location) noexcept {
  if (same_point(t.a, s.a) && same_point(t.b, s.b) && same_point(t.c, s.c)) return true;
  if (s_location != TriangleLocation::inside && s_location != TriangleLocation::outside &&
      s_location != TriangleLocation::none)
    return false;
  return is_vertex_of(t.a, s) && is_vertex_of(t.b, s) && is_vertex_of(t.c, s) && is_vertex_of(s.a, t) &&
         is_vertex_of(s.b, t) && is_vertex_of(s.c, t);
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
  const Triangle* best_triangle = nullptr;
  TriangleLocation best_location = TriangleLocation::none;
  double best_t = inf, bound = inf;
  // The values compared on ties, in two slots: the best hit's (when tied[best_slot] holds its triangle) and the
  // candidate's, so that neither is copied.
  TiedHit tied[2];
  int best_slot = 0;
  const Triangle* previous = nullptr;
  Candidate c{};
  BvhLeaf leaf;
  while (next_leaf(walk, bound, leaf)) {
    for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
      const Triangle& tri = triangles[leaf.position + n];
      if (previous != nullptr && repeats(tri, *previous, c.location)) {
        tracer.repeat();  // the same relation and t as the previous candidate
      } else {
        c = classify(ray, tri, rule);
        previous = &tri;
        tracer.candidate(c.stage);
      }
      if (c.relation != TriangleRelation::hit) continue;
      tracer.hit();
      const std::uint32_t k = leaf.triangles[n];
      if (found && same_t_by_vertices(tri, c.location, *best_triangle, best_location)) {
        // The same exact t as the best hit, hence the same RN(t): a tie, decided by the index.
        tracer.tie();
        tracer.tie_without_arithmetic();
        c.t = best_t;
        if (k > best) continue;
      } else {
        if (std::isnan(c.t)) c.t = hit_t(ray, tri, rule);
        if (found) {
          if (c.t > best_t) continue;
          if (c.t == best_t) {
            tracer.tie();
            TiedHit& held = tied[best_slot];
            TiedHit& candidate = tied[1 - best_slot];
            if (!held.holds(best_triangle)) held.reset(best_triangle);
            candidate.reset(&tri);
            const std::optional<TieOrder> certified = compare_tied_t(ray, candidate, held);
            const int order =  // the sign of t − t_best
                certified ? certified->sign : detail::exact::compare_triangle_t(ray, tri, *best_triangle);
            tracer.comparison(certified ? certified->stage : Stage::exact);
            if (order > 0 || (order == 0 && k > best)) continue;
            best_slot = 1 - best_slot;  // the candidate's slot, which holds the new best's values
          }
        }
      }
      found = true;
      best = k;
      best_position = static_cast<std::uint32_t>(leaf.position + n);
      best_triangle = &tri;
      best_location = c.location;
      best_t = c.t;
      bound = std::nextafter(c.t, inf);
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
