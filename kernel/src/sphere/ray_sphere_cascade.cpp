// The certified ray–sphere cascade. Each answer comes from the cheapest stage that decides it:
//   - the relation: first the binary64 filter of the signs of C and D (ray_sphere_filter.hpp; a miss it decides
//     returns at once, without expansions); then the signs of C and D read from their exact expansions
//     (ray_sphere_stages.hpp), or exact rationals when a product was not exact or a sign could not be read;
//   - both roots, when the filter decided D > 0 and C ≠ 0: candidates from the filter's values, one Newton step each
//     (one Lanes2 pass of the boundary filter, ray_sphere_boundary_filter.hpp), confirmed at the four midpoints
//     beside them in one Lanes4 pass; else each by the walk over its boundaries, one boundary filter at a time
//     (round_walking_to_midpoints); this whole filter stage runs before validation (sphere_intersection_filtered);
//   - each root otherwise: a candidate from the expansions' rounded values (the stable form: the root of larger magnitude
//     from −B ∓ √D, the other as C over it), decided at its rounding boundaries from the exact expansions of A,
//     B, C (core/quotient_boundary.hpp's round_walking_to_midpoints on the root's side, ray_sphere_stages.hpp);
//     a rational root (C = 0: 0 and −2B/A; the tangent root −B/A) as a quotient of expansions
//     (round_quotient_near); otherwise exact rationals and MPFR.
// Every answer is exact: the filters' signs are certified (proofs/sphere/SphereFilter.v, SphereBoundaryFilter.v),
// the expansions' are exact when the builder says so.
#include "sphere/ray_sphere_cascade.hpp"

#include "core/escalation.hpp"
#include "core/interval.hpp"
#include "core/multiversion.hpp"
#include "core/quotient_boundary.hpp"
#include "sphere/exact_sphere.hpp"
#include "sphere/ray_sphere_boundary_filter.hpp"
#include "sphere/ray_sphere_filter.hpp"
#include "sphere/ray_sphere_stages.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <optional>

namespace raykernel::detail {
namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();
// How many doubles a root's candidate may be off before the exact stage rounds it (the candidate's few roundings
// leave it within a few ulps unless a product underflows).
constexpr int max_walk = 8;

// The expansion's value rounded (the components summed from the smallest: close to its rounding; a candidate
// only, never a decision).
template <std::size_t N>
double approximate(const Expansion<N>& e) noexcept {
  double s = 0;
  for (std::size_t i = 0; i < e.size; ++i) s += e.component[i];
  return s;
}

// RN(num/den) for num = scale·B·(−1) and den = A > 0, from the candidate num ⊘ den; nothing when undecided.
std::optional<double> round_b_over_a(const SphereExpansions& s, double scale) noexcept {
  ExpansionBuilder builder;
  Expansion<24> num;
  builder.scale(s.b, -scale, num);
  builder.check_finite(num);
  const std::optional<Expansion<16>> short_num = shortened<16>(num);  // the quotient rounding's valid range
  if (!builder.exact() || !short_num) return std::nullopt;
  const double candidate = approximate(num) / approximate(s.a);
  if (!std::isfinite(candidate)) return std::nullopt;
  return round_quotient_near(*short_num, s.a, 1, candidate);
}

// RN of the root (−1: t1, +1: t2) for D > 0 and C ≠ 0, from the candidate; nothing when undecided.
std::optional<double> round_irrational_candidate(const SphereExpansions& s, int root, double candidate) noexcept {
  if (!std::isfinite(candidate)) return std::nullopt;
  return round_walking_to_midpoints([&](double x, double y) { return sphere_root_side(s, root, x, y); }, candidate,
                                    max_walk);
}

struct Roots {
  double t1, t2;
  Stage stage = Stage::expansion;  // the stage that rounded them (filter: both by the boundary filter)
};

// The candidates of both roots from approximations of A, B, C, D (D > 0, C ≠ 0): the root of larger magnitude
// is (−B − sign(B)·√D)/A, the other C/(−B − sign(B)·√D), with no cancellation. Never a decision.
Roots root_candidates(double a, double b, double c, double d) noexcept {
  const double w = b >= 0 ? -(b + std::sqrt(d)) : -b + std::sqrt(d);
  const double large = w / a, small = c / w;
  return b >= 0 ? Roots{large, small} : Roots{small, large};
}

// RN of the root (−1: t1, +1: t2; D > 0, C ≠ 0) from the boundary filter (ray_sphere_boundary_filter.hpp): a
// Newton step from the candidate, then the walk over the midpoints beside it; nothing when a sign it needs is
// uncertain. Multiversioned (FMA where the CPU has it: the filter's TwoProducts are fma; the same bits either way,
// core/multiversion.hpp); the lambda is inlined so that the FMA clone computes it with the instruction.
RAYKERNEL_MULTIVERSION
std::optional<double> filtered_root(const Ray& ray, const Sphere& sphere, int root, double candidate) noexcept {
  if (!std::isfinite(candidate)) return std::nullopt;
  const double t = sphere_root_newton_step(ray, sphere, candidate);
  return round_walking_to_midpoints(
      [&](double x, double y) __attribute__((always_inline)) {
        return sphere_root_side_filtered(ray, sphere, root, x, y);
      },
      t, max_walk);
}

// Both candidates at once (D > 0, C ≠ 0): one Newton step each, then the boundary filter at the four midpoints
// beside them in one Lanes4 pass
// (lanes: below t1, above t1, below t2, above t2). A candidate is RN of its root when the root lies strictly
// between its two midpoints, sign(t_k − lower) > 0 and sign(t_k − upper) < 0: the first step of
// round_walking_to_midpoints (core/quotient_boundary.hpp) when it returns the candidate, each side read by
// root_side_of from the lane's signs as sphere_root_side_filtered reads the scalar filter's. Nothing when either
// candidate is not confirmed so (then the Newton step and the walk decide, one boundary at a time).
//   Certified by (each lane the scalar filter's operations; the Newton step chooses where to look, decides nothing):
//     each lane's signs:  proofs/sphere/SphereBoundaryFilter.v, `sphere_boundary_q_sound`, `sphere_boundary_slope_sound`
//     the side of t_k:    proofs/sphere/SphereRoots.v, `root_side_of_smaller_correct`, `root_side_of_larger_correct`
//     m⁻ < t < m⁺ gives RN(t) = t̂ (round_at_midpoints' last case, twinned: runner routine quotient_boundary):
//                         proofs/core/MidpointRounding.v, `rn_between_midpoints`
// The body is always_inline and called from the multiversioned function only: clang rejects a call passing a
// Lanes4 by value from a target_clones clone to a function without that target.
[[gnu::always_inline]] inline std::optional<Roots> confirmed_candidates_body(const Ray& ray, const Sphere& sphere,
                                                                         const Roots& candidate) noexcept {
  // One Newton step of both candidates in one Lanes2 pass.
  const Lanes2 next = sphere_root_newton_step(ray, sphere, Lanes2{candidate.t1, candidate.t2});
  const double t[2] = {next[0], next[1]};
  double below[2], above[2];
  for (int k = 0; k < 2; ++k) {
    const double magnitude = std::fabs(t[k]);
    if (!(magnitude >= bounds::half_gap_min_magnitude && magnitude < bounds::largest_finite)) return std::nullopt;
    below[k] = next_down(t[k]);  // std::nextafter towards ∓DBL_MAX, for finite t (core/interval.hpp), inline
    above[k] = next_up(t[k]);
  }
  const SphereBoundaryLanes<Lanes4> b = sphere_boundary_filter_lanes<Lanes4>(
      ray, sphere, Lanes4{below[0], t[0], below[1], t[1]}, Lanes4{t[0], above[0], t[1], above[1]});
  bool confirmed = true;
  for (int lane = 0; lane < 4; ++lane) {
    const int root = lane < 2 ? -1 : +1;
    const std::int64_t q = b.q[lane], slope = b.slope[lane];
    const bool certain = q == -1 || (q == 1 && slope != uncertain_lane);
    const int side = certain ? root_side_of(root, static_cast<int>(q), q == 1 ? static_cast<int>(slope) : 0) : 0;
    confirmed = confirmed && (lane % 2 == 0 ? side > 0 : side < 0);
  }
  if (!confirmed) return std::nullopt;
  return Roots{t[0], t[1], Stage::filter};
}

RAYKERNEL_MULTIVERSION
std::optional<Roots> confirmed_candidates(const Ray& ray, const Sphere& sphere, const Roots& candidate) noexcept {
  return confirmed_candidates_body(ray, sphere, candidate);
}

// Both roots from the boundary filter, from the relation filter's candidates (Â, B̂, Ĉ, D̂: ulps off where
// B² − A·C cancels, which the Newton step repairs), when that filter decided D > 0 and C ≠ 0.
std::optional<Roots> filter_roots(const Ray& ray, const Sphere& sphere, const SphereFilterSigns& f) noexcept {
  if (f.d != Sign::positive || !is_certain(f.c)) return std::nullopt;
  const Roots candidate = root_candidates(f.a, f.b, f.c_value, f.d_value);
  if (const std::optional<Roots> r = confirmed_candidates(ray, sphere, candidate)) return r;
  const std::optional<double> t1 = filtered_root(ray, sphere, -1, candidate.t1);
  if (!t1) return std::nullopt;
  const std::optional<double> t2 = filtered_root(ray, sphere, +1, candidate.t2);
  if (!t2) return std::nullopt;
  return Roots{*t1, *t2, Stage::filter};
}

// Both roots from the expansion stage, or nothing (then the exact stage rounds them).
std::optional<Roots> expansion_roots(const Ray& ray, const Sphere& sphere, const SphereExpansions& s,
                                     const SphereClassification& c, bool filter_tried) noexcept {
  // The relation may come from the filter; the roots are read from the expansions only when they are exact (a
  // product that underflowed, such as a subnormal centre coordinate squared, leaves them approximate).
  if (!s.builder.exact()) return std::nullopt;
  if (c.relation == SphereRelation::tangent) {
    if (c.origin == SphereOrigin::on_surface) return Roots{0.0, 0.0};  // C = 0 and D = B² = 0: t0 = 0 exactly
    const std::optional<double> t0 = round_b_over_a(s, 1.0);
    if (!t0) return std::nullopt;
    return Roots{*t0, *t0};
  }
  const Sign b_sign = ExpansionBuilder::sign_or_compressed(s.b);
  if (!is_certain(b_sign)) return std::nullopt;
  if (c.origin == SphereOrigin::on_surface) {  // roots 0 and −2B/A (B ≠ 0, as D = B² > 0)
    const std::optional<double> other = round_b_over_a(s, 2.0);
    if (!other) return std::nullopt;
    return b_sign == Sign::negative ? Roots{0.0, *other} : Roots{*other, 0.0};
  }
  // Each root by the boundary filter first (cheap, and decisive unless the root is within ~2^-90 of a midpoint),
  // unless filter_roots has just tried it, then by the expansions' signs at the boundaries.
  const Roots candidate = root_candidates(approximate(s.a), approximate(s.b), approximate(s.c), approximate(s.d));
  bool filtered = !filter_tried;
  const auto round = [&](int root, double t) {
    if (filtered)
      if (const std::optional<double> r = filtered_root(ray, sphere, root, t)) return r;
    filtered = false;
    return round_irrational_candidate(s, root, t);
  };
  const std::optional<double> t1 = round(-1, candidate.t1);
  if (!t1) return std::nullopt;
  const std::optional<double> t2 = round(+1, candidate.t2);
  if (!t2) return std::nullopt;
  return Roots{*t1, *t2, filtered ? Stage::filter : Stage::expansion};
}

// The signs of C and D, each through the stages (core/escalation.hpp): the binary64 filter
// (proofs/sphere/SphereFilter.v: sphere_filter_c_sound, sphere_filter_d_sound), then the exact expansions,
// `expanded(false)` for C's sign and `expanded(true)` for D's (built on first use; read only when exact, by
// sign_or_compressed); nothing when a sign needs the exact stage.
template <class Expanded>
std::optional<TracedSphereClassification> classification(const SphereFilterSigns& f, Expanded expanded) noexcept {
  Escalation trace;
  const Sign c = trace.sign(SignStage{Stage::filter, [&] { return f.c; }},
                            SignStage{Stage::expansion, [&] { return expanded(false); }});
  const Sign d = trace.sign(SignStage{Stage::filter, [&] { return f.d; }},
                            SignStage{Stage::expansion, [&] { return expanded(true); }});
  if (!is_certain(c) || !is_certain(d)) return std::nullopt;
  return TracedSphereClassification{{sphere_origin(static_cast<int>(c)), sphere_relation(static_cast<int>(d))},
                                    trace.reached()};
}

// The expansions' signs of C and D (uncertain where the expansions are not exact), out of line: SphereExpansions
// takes 5 KB of stack, which the relation's frame should not carry (nor probe page by page) on every query.
struct ExpansionSigns {
  Sign c, d;
};
// The expansion stage's sign of C (d false) or D (d true): read only when the expansions are exact.
Sign expansion_sign(const SphereExpansions& s, bool d) noexcept {
  if (!s.builder.exact()) return Sign::uncertain;
  return d ? ExpansionBuilder::sign_or_compressed(s.d) : ExpansionBuilder::sign_or_compressed(s.c);
}
[[gnu::noinline]] ExpansionSigns expansion_signs(const Ray& ray, const Sphere& sphere) noexcept {
  SphereExpansions s;
  sphere_expansions(ray, sphere, s);
  return {expansion_sign(s, false), expansion_sign(s, true)};
}

// The lanes of a Mask2 where it is true, as bits 0 and 1.
[[gnu::always_inline]] inline std::uint32_t lane_bits(Mask2 m) noexcept {
#if defined(__SSE2__)
  return static_cast<std::uint32_t>(__builtin_ia32_movmskpd(reinterpret_cast<Lanes2>(m)));
#else
  return static_cast<std::uint32_t>(m[0] != 0) | (static_cast<std::uint32_t>(m[1] != 0) << 1);
#endif
}

}  // namespace

// Branch-free (written through classification() it measured 10% slower; with a branch per sign, which random
// queries mispredict, 40%): the two comparisons of each sign and the radius's give a 5-bit index into a table of
// packed answers (arithmetic on the bits, 25 instructions against 8, measured 13% slower).
namespace {
// Entry k: bit 0 C > E_C, bit 1 D > E_D, bit 2 C < −E_C, bit 3 D < −E_D, bit 4 r > 0. Certain when each sign has
// exactly one comparison and r > 0; SphereOrigin and SphereRelation are then 1 + the sign (inside 0, outside 2;
// miss 0, cross 2).
constexpr std::array<std::uint32_t, 32> packed_relations = [] {
  std::array<std::uint32_t, 32> t{};
  for (std::uint32_t k = 0; k < 32; ++k) {
    const std::uint32_t pos = k & 3, neg = (k >> 2) & 3;
    const std::uint32_t certain = static_cast<std::uint32_t>((pos | neg) == 3 && (pos & neg) == 0 && (k & 16) != 0);
    t[k] = (1 + (pos & 1) - (neg & 1)) | ((1 + (pos >> 1) - (neg >> 1)) << 8) | (certain << 16);
  }
  return t;
}();
}  // namespace

std::uint32_t fast_sphere_relation_packed(const Ray& ray, const Sphere& sphere) noexcept {
  static_assert(static_cast<int>(SphereOrigin::inside) == 0 && static_cast<int>(SphereOrigin::outside) == 2 &&
                static_cast<int>(SphereRelation::miss) == 0 && static_cast<int>(SphereRelation::cross) == 2);
  const SphereFilterSigns f = sphere_filter(ray, sphere);
  const Lanes2 value{f.c_value, f.d_value}, bound{f.c_bound, f.d_bound};
  // movmskpd on x86: the two comparisons of each direction in one instruction.
  const std::uint32_t pos = lane_bits(value > bound), neg = lane_bits(value < -bound);
  return packed_relations[pos | (neg << 2) | (static_cast<std::uint32_t>(sphere.radius > 0) << 4)];
}

TracedSphereClassification sphere_relation_cascade(const Ray& ray, const Sphere& sphere) {
  std::optional<ExpansionSigns> signs;
  const auto expanded = [&](bool d) {
    if (!signs) signs = expansion_signs(ray, sphere);
    return d ? signs->d : signs->c;
  };
  if (const std::optional<TracedSphereClassification> c = classification(sphere_filter(ray, sphere), expanded)) return *c;
  return {exact::classify_sphere(ray, sphere), Stage::exact};
}

namespace {

// The cascade after the filter (SphereExpansions takes 5 KB of stack, which the filter's path should not carry, nor
// probe page by page, on every query): the signs of C and D escalated, the roots from the boundary filter or the
// expansions, else the exact stage.
[[gnu::noinline]] SphereStages intersection_with_expansions(const Ray& ray, const Sphere& sphere,
                                                            const SphereFilterSigns& signs, SphereIntersection& out) {
  SphereExpansions s;
  bool built = false;
  const auto build = [&] {
    if (!built) sphere_expansions(ray, sphere, s);
    built = true;
  };
  const std::optional<TracedSphereClassification> c = classification(signs, [&](bool d) {
    build();
    return expansion_sign(s, d);
  });
  if (!c) {
    out = exact::intersect_sphere(ray, sphere);
    return {Stage::exact, Stage::exact};
  }
  const SphereClassification& k = c->classification;
  const Stage relation_stage = c->stage;
  const auto answer = [&](double t1, double t2, Stage rounding_stage) {
    out = {k.origin, k.relation, t1, t2};
    return SphereStages{relation_stage, rounding_stage};
  };
  if (k.relation == SphereRelation::miss) return answer(not_a_number, not_a_number, relation_stage);
  const bool filter_tried = relation_stage == Stage::filter;  // both signs from the filter: D > 0 or D = 0, C certain
  // D's expansion is built even when the filter decided the relation: its rounded value makes the roots'
  // candidates a rounding or two from the roots (the filter's D̂ can be far off where B² − A·C cancels, and
  // a candidate further off costs a boundary sign per ulp; measured in bench/README.md).
  build();
  if (const std::optional<Roots> r = expansion_roots(ray, sphere, s, k, filter_tried))
    return answer(r->t1, r->t2, r->stage);
  const SphereIntersection exact = exact::intersect_sphere(ray, sphere);
  return answer(exact.t1, exact.t2, Stage::exact);
}

}  // namespace

bool sphere_intersection_filtered(const Ray& ray, const Sphere& sphere, SphereIntersection& out) noexcept {
  const SphereFilterSigns signs = sphere_filter(ray, sphere);
  // Both signs from the filter (the escalation asks no later stage), then a miss, or both roots from the boundary
  // filter, answer here.
  const std::optional<TracedSphereClassification> c = classification(signs, [](bool) { return Sign::uncertain; });
  if (!c || !(sphere.radius > 0)) return false;
  const SphereClassification& k = c->classification;
  if (k.relation == SphereRelation::miss) {
    out = {k.origin, k.relation, not_a_number, not_a_number};
    return true;
  }
  if (const std::optional<Roots> r = filter_roots(ray, sphere, signs)) {
    out = {k.origin, k.relation, r->t1, r->t2};
    return true;
  }
  return false;
}

SphereStages sphere_intersection_after_filter(const Ray& ray, const Sphere& sphere, SphereIntersection& out) {
  return intersection_with_expansions(ray, sphere, sphere_filter(ray, sphere), out);
}

SphereStages sphere_intersection_cascade(const Ray& ray, const Sphere& sphere, SphereIntersection& out) {
  if (sphere_intersection_filtered(ray, sphere, out)) return {Stage::filter, Stage::filter};
  return sphere_intersection_after_filter(ray, sphere, out);
}

int sphere_root_side_of(const Ray& ray, const Sphere& sphere, int root, double b) {
  SphereExpansions s;
  sphere_abc_expansions(ray, sphere, s);  // the side of a root needs A, B, C only
  if (s.builder.exact()) {
    const Sign side = sphere_root_side(s, root < 0 ? -1 : +1, b, b);
    if (is_certain(side)) return static_cast<int>(side);
  }
  return exact::root_side_of_midpoint(ray, sphere, root < 0 ? -1 : +1, b, b);
}

std::optional<SphereRootHit> sphere_hit_in_interval(const Ray& ray, const Sphere& sphere, const SphereIntersection& r,
                                                    const RayInterval& interval) {
  if (r.relation == SphereRelation::miss) return std::nullopt;
  const auto within = [&](int root, double rounded) {
    const auto side = [&](double b) {
      return rounded < b ? -1 : rounded > b ? 1 : sphere_root_side_of(ray, sphere, root, b);
    };
    if (side(interval.t_min) < 0) return false;
    // Every root is below +inf (a root beyond the doubles rounds to +inf but is finite).
    return std::isinf(interval.t_max) || side(interval.t_max) <= 0;  // a valid t_max is +inf or finite
  };
  if (within(-1, r.t1)) return SphereRootHit{-1, r.t1};
  if (r.relation == SphereRelation::cross && within(+1, r.t2)) return SphereRootHit{+1, r.t2};
  return std::nullopt;
}

bool segment_meets_sphere(const Vec3& p, const Vec3& q, const Sphere& sphere) {
  // sign(C) of the filter does not depend on the ray's direction (proofs/sphere/SphereFilter.v,
  // sphere_filter_c_sound, for every input): any nonzero one serves. A certain sign is never zero.
  const Vec3 any_direction{1, 0, 0};
  const Sign c_p = sphere_filter(Ray{p, any_direction}, sphere).c;
  const Sign c_q = sphere_filter(Ray{q, any_direction}, sphere).c;
  if (is_certain(c_p) && is_certain(c_q)) {
    if (c_p != c_q) return true;                  // q(0)·q(1) < 0: a root in (0, 1)
    if (c_p == Sign::negative) return false;      // q < 0 at both ends, so on [0, 1]: no root there
  }
  return exact::segment_meets_sphere(p, q, sphere);
}

}  // namespace raykernel::detail
