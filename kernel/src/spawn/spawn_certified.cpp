// The certified fast path of spawn and spawn_to (docs/contract.md §9): the exact path's answer (spawn.cpp) from
// the shared stages, or nothing. Every decision below is one of an exact value's sign or a correct rounding,
// certified; what is not certain (and every invalid input) goes to the exact path, which decides it in GMP.
//
//   s        spawn: sign(w·N) = the ray–triangle den of the ray (a, w): its stage-2 enclosure, then its exact
//            expansion (triangle/ray_triangle_stages.hpp). spawn_to: σ(q).
//   σ(x)     sign((x − a)·N) = −orient3d(x; a, b, c), since det(a − x, b − x, c − x) = (a − x)·N: the orientation's
//            filter, exact expansions, then rationals (orient/orient_predicates.hpp's orient3d_sign).
//   P̂        binary64, a ray crossing: each P_k = o_k + (num/den)·d_k = (o_k·den + d_k·num)/den rounded to
//            nearest-even by round_quotient (core/quotient_rounding.hpp) from affine_enclosure's enclosure of the
//            numerator (spawn_certified.hpp) and den's, over one divisor; when that cannot certify (P_k close to a
//            midpoint), by its sides at the midpoints of a candidate and its neighbours
//            (core/quotient_boundary.hpp's round_walking_to_midpoints).
//            The side of P_k against m = (x + y)/2 is sign(den)·sign(Δ), Δ = num·(2d_k) − (x + y − 2o_k)·den
//            (`midpoint_side_sign`): the order of the quotients num/den and (x + y − 2o_k)/(2d_k), decided from
//            the triangle's stage-2 enclosures of num and den and midpoint_offset's enclosure of x + y − 2o_k by
//            compare_quotients_compensated (nearest/compare_quotients.hpp). d_k = 0 gives P_k = o_k exactly.
//            binary32: RN32(P_k) from r = RN64(P_k): RN32(r) unless r is a binary32 midpoint
//            (`binary32_through_binary64`), else the binary32 value on P_k's side of r, the side being the same
//            test at m = r (`binary32_midpoint_side`). A point p: P̂ = p (binary64), RN32(p) (the conversion).
//   steps    σ(P̂) = s: k = 0. Otherwise the axis i of the largest |N_i| (N's components as exact expansions, their
//            magnitudes compared exactly) and δ = sign(N_i)·s; then P̂ moved one value of the format at a time
//            along axis i (spawn/format_steps.hpp): the smallest number k of moves that gives σ = s, σ being
//            monotone along the axis, found by doubling and bisecting k with σ tested exactly at each.
//
// Error bound: none of its own beyond affine_enclosure's and midpoint_offset's (spawn_certified.hpp); the signs are exact or certified by
//   their stages' bounds.
// Valid range: every input; what a stage cannot certify (ties at a midpoint of the format, |P_k| < 2^-968, an
//   overflow, den or w·N too close to 0 for stage 2 and inexact in expansions) returns nothing.
// Certified by:
//   proofs/spawn/SpawnAffine.v, `affine_enclosure_sound`;
//   proofs/spawn/SpawnTwins.v, `midpoint_offset_twin_sound`, `affine_enclosure_twin_sound` (the twins of
//   midpoint_offset and affine_enclosure, spawn_certified.hpp; differential runner, group spawn);
//   proofs/plane/QuotientRounding.v, `round_quotient_sound`;
//   proofs/spawn/SpawnRounding.v, `midpoint_offset_encloses`, `midpoint_side_sign`, `binary32_through_binary64`;
//   proofs/spawn/SpawnRounding.v, `binary32_midpoint_side`;
//   proofs/compare/CompareQuotients.v, `compare_quotients_compensated_enclosure`;
//   proofs/plane/PlaneCompensated.v, `enclosure_sign_sound`, `compensated_dot3_enclosure`;
//   proofs/triangle/TriangleCompensated.v, `den_compensated_encloses`, `num_compensated_encloses`;
//   proofs/core/MidpointRounding.v, `boundary_decision_correct`;
//   proofs/orient/OrientFilter.v, `orient3d_filter_sound`;
//   proofs/triangle/TriangleStage3Twins.v, `triangle_expansion_sign_sound`, `value_ev_exact`.
//   The property tests (tests/spawn_test.cpp) check every answer against spawn_exact, bit for bit.
//
// Compiled with -ffp-contract=off and without fast-math (kernel/CMakeLists.txt).
#include "spawn/spawn_certified.hpp"

#include "core/eft.hpp"
#include "core/dot3_compensated.hpp"
#include "core/enclosure.hpp"
#include "core/escalation.hpp"
#include "core/expansion_value.hpp"
#include "core/multiversion.hpp"
#include "core/quotient_boundary.hpp"
#include "core/quotient_rounding.hpp"
#include "core/sign.hpp"
#include "core/validation.hpp"
#include "nearest/compare_quotients.hpp"
#include "orient/orient_predicates.hpp"
#include "spawn/format_steps.hpp"
#include "triangle/ray_triangle_formula.hpp"
#include "triangle/ray_triangle_stages.hpp"

#include <array>
#include <cstdint>
#include <cmath>
#include <optional>

namespace raykernel::detail {
namespace {

// The largest number of moves searched here (2^61, so that the doubling stays within int64; the end of the format's
// range bounds the search too, below). A larger k, possible only across most of the range, goes to the exact path.
constexpr std::int64_t max_certified_steps = std::int64_t{1} << 61;
constexpr int max_candidate_walk = 3;

[[nodiscard]] double& coordinate(Vec3& v, int k) noexcept { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }
[[nodiscard]] double coordinate(const Vec3& v, int k) noexcept { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

// σ(x) = sign((x − a)·N): stage 2 of the ray–triangle num of a ray from x, (a − x)·N, of the opposite sign
// (triangle/ray_triangle_stages.hpp); then the orientation's stages (orient/orient_predicates.hpp's orient3d_sign:
// filter, exact expansions, rationals), as −orient3d(x; a, b, c), since det(a − x, b − x, c − x) = (a − x)·N.
RAYKERNEL_MULTIVERSION Sign plane_side_compensated(const Vec3& x, const Triangle& t) noexcept {
  const Sign num = enclosure_sign(triangle_num_compensated(x, t));
  return is_certain(num) ? static_cast<Sign>(-static_cast<int>(num)) : Sign::uncertain;
}
[[nodiscard]] int plane_side_of(const Vec3& x, const Triangle& t) {
  return Escalation{}.exact_sign([&] { return -mesh_detail::orient3d_sign(x, t.a, t.b, t.c); },
                                 SignStage{Stage::compensated, [&] { return plane_side_compensated(x, t); }});
}

// sign(w·N): the ray–triangle den of a ray along w, from stage 2, then from its exact expansion; 0 when neither is
// certain or it is exactly 0 (invalid input: the exact path names it).
RAYKERNEL_MULTIVERSION Sign direction_side_compensated(const Vec3& w, const Triangle& t) noexcept {
  return enclosure_sign(triangle_den_compensated(w, t));
}
[[nodiscard]] int direction_side_of(const Vec3& w, const Triangle& t) noexcept {
  const Sign s = Escalation{}.sign(
      SignStage{Stage::compensated, [&] { return direction_side_compensated(w, t); }},
      SignStage{Stage::expansion, [&] { return value_expansion(Ray{t.a, w}, t, value_den).sign(); }});
  return is_certain(s) ? static_cast<int>(s) : 0;
}

// One coordinate of the crossing P = o + (num/den)·d: its side against midpoints, and a candidate for RN(P_k).
struct CrossingCoordinate {
  Enclosure num, den;
  int den_sign;
  double o, d;

  // sign(P_k − (x + y)/2) = sign(den)·sign(num·(2d) − (x + y − 2o)·den) (`midpoint_side_sign`), or uncertain
  // (never zero: enclosure_sign does not certify it; an exact tie goes to the exact path).
  [[nodiscard]] Sign operator()(double x, double y) const noexcept {
    const Enclosure twice_d{2 * d, 0, 0};
    const Sign delta = enclosure_sign(compare_quotients_compensated(num, den, midpoint_offset(x, y, o), twice_d));
    if (!is_certain(delta)) return Sign::uncertain;
    return static_cast<Sign>(static_cast<int>(delta) * den_sign);
  }

  // o + t·d with t ≈ num/den in double-double: within an ulp or two of P_k in the common case (the walk checks it).
  [[nodiscard]] double candidate() const noexcept {
    const double t1 = num.hi / den.hi;
    const double t2 = (std::fma(-t1, den.hi, num.hi) + (num.lo - t1 * den.lo)) / den.hi;  // (num − t1·den)/den
    const DoubleDouble p = two_prod(t1, d);
    const DoubleDouble s = two_sum(o, p.hi);
    return s.hi + (s.lo + (p.lo + t2 * d));
  }
};

// RN32(x) for a double x (the conversion), or nothing beyond the largest finite float: there the conversion is
// undefined in C++ (the compiler may assume a finite result), and the exact path decides (and names an overflow).
[[nodiscard]] std::optional<double> to_binary32(double x) noexcept {
  const double largest = spawn_steps::from_ordinal(
      static_cast<std::int64_t>(spawn_steps::largest_ordinal(OriginFormat::binary32)), OriginFormat::binary32);
  if (!(std::fabs(x) <= largest)) return std::nullopt;
  return static_cast<float>(x);
}

// RN32(X) from r = RN64(X) and `side`, the sign of X against midpoints (`binary32_through_binary64`,
// `binary32_midpoint_side`); nothing when it overflows binary32 or the side at a binary32 midpoint is uncertain.
template <class Side>
[[nodiscard]] std::optional<double> round_binary32_from_binary64(double r, const Side& side) noexcept {
  const std::optional<double> rounded = to_binary32(r);  // RN32(r)
  if (!rounded) return std::nullopt;
  const double f = *rounded;
  if (f == r) return f;
  const double g = spawn_steps::step(f, r > f ? 1 : -1, OriginFormat::binary32);  // r's other binary32 neighbour
  if (!std::isfinite(g) || f + g != 2 * r) return f;  // not a midpoint (f + g and 2r are exact)
  const Sign above = side(r, r);                       // sign(X − r)
  if (above == Sign::zero) return f;                    // X = r: ties to even, as the conversion rounds r
  if (!is_certain(above)) return std::nullopt;
  return (above == Sign::positive) == (g > f) ? g : f;
}

// P̂, or nothing.
RAYKERNEL_MULTIVERSION std::optional<Vec3> rounded_hit(const HitPoint& hit, const Triangle& source, OriginFormat format) noexcept {
  const bool binary32 = format == OriginFormat::binary32;
  if (hit.kind == HitPoint::Kind::point) {
    if (!is_finite(hit.point)) return std::nullopt;
    if (!binary32) return hit.point;
    const std::optional<double> x = to_binary32(hit.point.x), y = to_binary32(hit.point.y), z = to_binary32(hit.point.z);
    if (!x || !y || !z) return std::nullopt;
    return Vec3{*x, *y, *z};
  }
  if (!all_finite(hit.ray)) return std::nullopt;
  const TriangleQuotientStage2 values = triangle_quotient_compensated(hit.ray, source);
  const Enclosure& den = values.den;
  const Sign den_sign = enclosure_sign(den);
  if (!is_certain(den_sign)) return std::nullopt;
  const Divisor divisor = prepare_divisor(den);
  Vec3 rounded{};
  for (int k = 0; k < 3; ++k) {
    const double o = coordinate(hit.ray.origin, k), d = coordinate(hit.ray.direction, k);
    std::optional<double> r;
    if (d == 0) {
      r = o;  // P_k = o_k exactly: its side against r = o_k is 0
      if (binary32) r = round_binary32_from_binary64(o, [](double, double) { return Sign::zero; });
    } else {
      // P_k = (o_k·den + d_k·num)/den: round_quotient on an enclosure of the numerator over den (one divisor for
      // the three coordinates); where it cannot certify (P_k near a midpoint), the sides at the midpoints.
      const CrossingCoordinate side{values.num, den, static_cast<int>(den_sign), o, d};
      r = round_quotient_if_certain(affine_enclosure(o, den, d, values.num), divisor);
      if (!r) r = round_walking_to_midpoints(side, side.candidate(), max_candidate_walk);
      if (r && binary32) r = round_binary32_from_binary64(*r, side);
    }
    if (!r) return std::nullopt;
    coordinate(rounded, k) = *r;
  }
  return rounded;
}

// The axis of the largest |N_i| (the smallest i on an exact tie) and sign(N_i), from N's exact expansions; nothing
// when an expansion is not exact (an underflow).
struct Axis {
  int index;
  int sign;
};
[[nodiscard]] std::optional<Axis> largest_normal_axis(const Triangle& t) noexcept {
  const auto leaves = [&t](const Vec3& v) {
    return std::array<ExpansionValue<2>, 3>{expansion_difference(v.x, t.a.x), expansion_difference(v.y, t.a.y),
                                            expansion_difference(v.z, t.a.z)};
  };
  auto normal = cross_terms(leaves(t.b), leaves(t.c));
  std::array<int, 3> sign{};
  for (int k = 0; k < 3; ++k) {
    const Sign s = normal[static_cast<std::size_t>(k)].sign();
    if (!is_certain(s)) return std::nullopt;
    sign[static_cast<std::size_t>(k)] = static_cast<int>(s);
    if (s == Sign::negative) normal[static_cast<std::size_t>(k)] = -normal[static_cast<std::size_t>(k)];  // |N_k|
  }
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    const Sign larger = (normal[static_cast<std::size_t>(k)] - normal[static_cast<std::size_t>(best)]).sign();
    if (!is_certain(larger)) return std::nullopt;
    if (larger == Sign::positive) best = k;
  }
  return Axis{best, sign[static_cast<std::size_t>(best)]};
}

}  // namespace

std::optional<SpawnedOrigin> spawn_certified(const HitPoint& hit, const Triangle& source, bool to_target,
                                             const Vec3& w_or_q, OriginFormat format) {
  if (!is_valid(source) || !is_finite(w_or_q)) return std::nullopt;  // is_valid(Triangle): its vertices finite
  const std::optional<Vec3> rounded = rounded_hit(hit, source, format);
  if (!rounded) return std::nullopt;
  // s ≠ 0 also certifies N ≠ 0 (and w ≠ 0); den ≠ 0 in rounded_hit certified d ≠ 0.
  const int s = to_target ? plane_side_of(w_or_q, source) : direction_side_of(w_or_q, source);
  if (s == 0) return std::nullopt;
  if (plane_side_of(*rounded, source) == s) return SpawnedOrigin{*rounded, 0};

  const std::optional<Axis> axis = largest_normal_axis(source);
  if (!axis) return std::nullopt;
  // σ along axis i is the sign of an affine function of x_i with slope N_i ≠ 0, and the values of the format are
  // in order: once a move gives σ = s, every further move does. So "σ = s after k moves" is false, then true, and
  // the smallest k is found by doubling k, then bisecting — each k tested exactly (a few tests for k = 1 or 2,
  // about 2·log2(k) for large k: a coordinate far smaller than the others).
  const int delta = axis->sign * s;
  const std::int64_t start = spawn_steps::ordinal(coordinate(*rounded, axis->index), format);
  Vec3 origin = *rounded;
  // The finite values left after P̂_i in direction δ: ordinals run from −m to m, m that of the largest finite
  // value (below 2^63); the differences are taken modulo 2^64, where they are exact (below 2^64).
  const std::uint64_t largest = spawn_steps::largest_ordinal(format);
  const std::uint64_t room =
      delta > 0 ? largest - static_cast<std::uint64_t>(start) : static_cast<std::uint64_t>(start) + largest;
  const auto place = [&](std::int64_t k) {  // the origin: P̂ moved k ≤ room values of the format along axis i
    const auto steps = static_cast<std::uint64_t>(k);
    const std::uint64_t target = delta > 0 ? static_cast<std::uint64_t>(start) + steps
                                           : static_cast<std::uint64_t>(start) - steps;
    coordinate(origin, axis->index) = spawn_steps::from_ordinal(static_cast<std::int64_t>(target), format);
  };
  const auto moved = [&](std::int64_t k) {  // whether σ = s after k moves
    place(k);
    return plane_side_of(origin, source) == s;
  };
  std::int64_t below = 0, above = 1;  // σ ≠ s after `below` moves; `above` is the next candidate
  while (true) {
    // Beyond the largest finite value, or too many moves for this search: the exact path decides (and names it).
    if (static_cast<std::uint64_t>(above) > room || above > max_certified_steps) return std::nullopt;
    if (moved(above)) break;
    below = above;
    above *= 2;
  }
  while (above - below > 1) {  // σ ≠ s after `below` moves, σ = s after `above`
    const std::int64_t middle = below + (above - below) / 2;
    (moved(middle) ? above : below) = middle;
  }
  place(above);
  return SpawnedOrigin{origin, static_cast<std::uint64_t>(above)};
}

}  // namespace raykernel::detail
