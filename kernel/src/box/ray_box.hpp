// The certified ray–box test of the BVH traversal: never rejects a box the exact ray meets.
//
// ---------------------------------------------------------------------------------------------------------
// ray_box_entry — conservative slab test with outward-rounded slab distances
//
// Question. For the ray o + t·d and the box [lo, hi] (all doubles), t in [t0, t1] with 0 ≤ t0 ≤ t1 (doubles,
// t1 may be +inf): is there a real t* in [t0, t1] with lo_i ≤ o_i + t*·d_i ≤ hi_i on every axis i? Answer
// "maybe" with a lower bound of the smallest such t*, or "no". Error bound: "no" only when no such t* exists
// (one-sided; "maybe" may be wrong). Valid range: every double input, with the per-ray set-up below.
// Certified by: the argument below, step by step (IEEE-754 binary64, round to nearest even, gradual
// underflow, as fixed by kernel/CMakeLists.txt and checked by core/fp_requirements.hpp); exercised by
// tests/bvh_test.cpp against exact rational arithmetic, and Coq: proofs/box/RayBox.v (`near_bound_sound`,
// `far_bound_sound`, `ray_box_sound`; on the BVH's binary32 boxes rounded outward, `slab_sound_outward`); over the
// bits, proofs/box/RayBoxTwins.v (`near_bound_twin_model`, `far_bound_twin_model`, `make_slab_case_b`,
// `near_bound_twin_sound`, `far_bound_twin_sound`, `ray_box_entry_twin_sound`), whose twins of make_slabs,
// ray_box_axis and ray_box_entry the differential runner checks bit for bit (group `box`: make_slabs, the scalar
// ray_box_entry, and ray_box_entries8 of every instruction set, lane by lane).
//
// Notation: RN is round to nearest even, u = 2^-53, η = 2^-1075 (half the smallest subnormal). For a real x
// whose rounding does not overflow: RN(x) = x(1 + ε) + δ with |ε| ≤ u, |δ| ≤ η, and δ = 0 unless
// |RN(x)| < 2^-1022 (Flocq: error_N_FLT). A sum or difference of two doubles has δ = 0 (when its result is
// subnormal it is exact). RN is monotone and odd, so RN keeps the sign of x (and RN(x) = 0 only if x is
// tiny, or for differences only if x = 0).
//
// Per axis i, with the slab planes in the order the ray crosses them — near = lo_i, far = hi_i when d_i is
// +0 or positive, near = hi_i, far = lo_i when d_i is −0 or negative (its sign bit) — the exact slab
// parameters are T_near = (near − o_i)/d_i ≤ T_far = (far − o_i)/d_i (for d_i ≠ 0), and the code computes
//
//     inv = RN(1/d_i)                                    (once per ray)
//     p   = RN(RN(plane − o_i) · inv)                    for plane = near and far
//     near_lo = RN(RN(p_near · K_lo) − τ)                K_lo = 1 − 2^-50, τ = 2^-1022
//     far_hi  = RN(RN(p_far · K_hi) + τ)                 K_hi = 1 + 2^-50
//     t0 = max(t0, near_lo),  t1 = min(t1, far_hi)       (a NaN operand leaves t0, t1 unchanged)
//
// and answers "maybe" iff t0 ≤ t1 after the three axes, with t0 as the entry bound. Claim: if some t* in
// [t0, t1] lies in every slab, then on every axis near_lo ≤ t* (or is NaN) and far_hi ≥ t* (or is NaN), so
// the final t0 ≤ t* ≤ t1 and the answer is "maybe" with t0 ≤ t*. Since this holds for every such t*, t0 is
// at most the smallest one: the exact entry t.
//
// Case A, d_i = ±0 (inv = ±inf, exact). The slab holds the whole line or none of it: lo_i ≤ o_i ≤ hi_i.
// RN(plane − o_i) has the sign of plane − o_i and is 0 only when plane = o_i (a difference of doubles
// rounds to 0 only when it is 0; an overflow to ±inf keeps the sign). Then p is ±inf with the sign of
// (plane − o_i)·d_i — the sign the limit d_i → ±0 gives — or NaN (0·inf) when o_i is on the plane. With
// d_i = +0: o_i < lo_i gives p_near = +inf, so t0 = +inf > t1 (unless t1 = +inf too, which only loses
// efficiency) — correct, the slab is missed; o_i > hi_i gives p_far = −inf, so t1 = −inf < t0 — correct;
// lo_i ≤ o_i ≤ hi_i gives p_near ∈ {−inf, NaN}, p_far ∈ {+inf, NaN}, which leave t0 and t1 alone. With
// d_i = −0 the planes swap and the signs flip: the same three cases. ∞·K ∓ τ = ∞ and NaN stays NaN.
//
// Case B, 2^-1022 ≤ |d_i| ≤ 2^1022 and the overflow guard G = RN(RN(M_i + |o_i|) · |inv|) ≤ 2^1022 holds,
// M_i ≥ |lo_i|, |hi_i| for every box tested (the root box's magnitude; for the BVH's binary32 boxes, that of
// the root box rounded outward, which contains them all).
//  B1. inv = (1/d_i)(1 + ε1): 1/d_i is in [2^-1022, 2^1022], a normal range, so δ = 0 and no overflow.
//  B2. |plane − o_i| ≤ M_i + |o_i|, so by monotonicity |RN(plane − o_i)| ≤ RN(M_i + |o_i|) and
//      |RN(plane − o_i) · inv| ≤ RN(M_i + |o_i|)·|inv|, hence |p| ≤ G ≤ 2^1022: nothing overflows,
//      RN(plane − o_i) = (plane − o_i)(1 + ε2) (difference: δ = 0), and
//      p = T·(1 + ε1)(1 + ε2)(1 + ε3) + δ3 with T the exact slab parameter, |δ3| ≤ η; p has T's sign or is 0.
//  B3. near, T = T_near ≥ 0: then p ≥ 0 and p ≤ T(1 + u)^3 + η. a = RN(p·K_lo) ≤ p·K_lo(1 + u) + η.
//      If a ≤ τ, near_lo = RN(a − τ) ≤ 0 ≤ T. Otherwise a − τ > 0 is a difference of doubles, so
//      near_lo ≤ (a − τ)(1 + u) ≤ (T·K_lo(1 + u)^4 + η(K_lo(1 + u) + 1) − τ)(1 + u)
//               ≤ T·K_lo(1 + u)^5 + (2.1η − τ)(1 + u) ≤ T,
//      since K_lo(1 + u)^5 ≤ (1 − 8u)(1 + 6u) < 1 and τ = 2^-1022 ≫ 2.1η.
//      near, T < 0: p ≤ 0, a ≤ 0, a − τ ≤ −τ < 0, near_lo < 0 ≤ t0 ≤ t*: harmless. So in both cases
//      near_lo ≤ max(T_near, 0) ≤ t* (t* ≥ t0 ≥ 0 and t* ≥ T_near because t* is in the slab).
//  B4. far, T = T_far ≥ t* ≥ 0: p ≥ 0 and p ≥ T(1 − u)^3 − η. b = RN(p·K_hi) ≥ p·K_hi(1 − u) − η ≥ 0
//      (b ≥ 0: RN is monotone and RN(0) = 0). b + τ ≥ 2^-1022 is normal, and far_hi = RN(b + τ) ≥ (b + τ)(1 − u)
//      ≥ T·K_hi(1 − u)^5 + (τ − η(K_hi(1 − u) + 1))(1 − u) ≥ T, since K_hi(1 − u)^5 ≥ (1 + 8u)(1 − 5u) > 1.
//      No overflow: |p| ≤ 2^1022 so b ≤ 2^1022(1 + 2^-50)(1 + u) and b + τ stay below 2^1023.
//
// Case C, every other axis (|d_i| outside [2^-1022, 2^1022], or the guard fails: a huge origin or box, or a
// direction component so small that a slab parameter could overflow): inv = NaN, the axis is left out.
// Leaving a slab out only enlarges the set of t the test accepts, so it never rejects a met box; it costs
// efficiency for such (rare) rays only.
//
// With t0 ≥ 0 throughout, NaN and ±inf handled as above, the claim follows axis by axis. The comparisons
// `x > t0 ? x : t0` and `x < t1 ? x : t1` keep t0, t1 when x is NaN; -ffp-contract=off keeps each RN above
// a separate rounding (a fused p·K ∓ τ would only round once, which the argument also covers).
// ---------------------------------------------------------------------------------------------------------
#pragma once

#include "core/lanes.hpp"

#include <raykernel/bvh.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace raykernel::bounds {

// The outward factors and the absolute term of ray_box_entry (derivation: B3, B4 above). K_lo(1 + u)^5 < 1
// and K_hi(1 − u)^4 > 1 need only K = 1 ∓ 6u; 1 ∓ 8u = 1 ∓ 2^-50 leaves a margin and is exact.
inline constexpr double ray_box_near_factor = 1.0 - 0x1p-50;  // K_lo
inline constexpr double ray_box_far_factor = 1.0 + 0x1p-50;   // K_hi
inline constexpr double ray_box_absolute = 0x1p-1022;         // τ: absorbs the underflow error η of p
// Case B's range: 1/d is normal and finite for |d| in [2^-1022, 2^1022]; |p| ≤ 2^1022 keeps p·K_hi + τ finite.
inline constexpr double ray_box_min_direction = 0x1p-1022;
inline constexpr double ray_box_max_direction = 0x1p1022;
inline constexpr double ray_box_max_parameter = 0x1p1022;

}  // namespace raykernel::bounds

namespace raykernel::mesh_detail {

// The per-ray set-up (cases A, B, C).
inline BvhRayTraversal::Slabs make_slabs(const Ray& ray, const std::array<double, 3>& magnitude) {
  BvhRayTraversal::Slabs s{};
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  for (int i = 0; i < 3; ++i) {
    s.origin[static_cast<std::size_t>(i)] = o[i];
    s.enters_at_hi[static_cast<std::size_t>(i)] = std::signbit(d[i]);
    double inv;
    const double a = std::fabs(d[i]);
    if (a == 0) {
      inv = std::copysign(std::numeric_limits<double>::infinity(), d[i]);  // case A
    } else if (a >= bounds::ray_box_min_direction && a <= bounds::ray_box_max_direction) {
      inv = 1.0 / d[i];
      const double guard = (magnitude[static_cast<std::size_t>(i)] + std::fabs(o[i])) * std::fabs(inv);
      if (!(guard <= bounds::ray_box_max_parameter)) inv = std::numeric_limits<double>::quiet_NaN();  // case C
    } else {
      inv = std::numeric_limits<double>::quiet_NaN();  // case C
    }
    s.inverse_direction[static_cast<std::size_t>(i)] = inv;
  }
  return s;
}

// One axis of ray_box_entry, written once for one box (V = double) and for the children of a node, several at
// once (V = Lanes8, Lanes4 or Lanes2, one box per lane): every lane performs exactly these operations in this
// order, so the argument above and proofs/box/RayBox.v (`slab_sound`, `ray_box_sound`) hold lane by lane. `select(m, x, t)`
// keeps t where the comparison is false, in particular where x is NaN.
template <class V>
[[gnu::always_inline]] inline void ray_box_axis(V near_plane, V far_plane, V origin, V inverse, V& t0, V& t1) noexcept {
  const V p_near = (near_plane - origin) * inverse;
  const V p_far = (far_plane - origin) * inverse;
  const V near_lo = p_near * bounds::ray_box_near_factor - bounds::ray_box_absolute;
  const V far_hi = p_far * bounds::ray_box_far_factor + bounds::ray_box_absolute;
  t0 = detail::select(near_lo > t0, near_lo, t0);
  t1 = detail::select(far_hi < t1, far_hi, t1);
}

// ray_box_entry: true when the ray may meet the box at some t in [t0, t1]; `entry` is then ≤ the exact entry.
// The box is read as the six doubles lo.x, lo.y, lo.z, hi.x, hi.y, hi.z (Box3's layout); the near face of
// axis i is element i, or i + 3 when the ray enters at the upper face.
static_assert(sizeof(Box3) == 6 * sizeof(double) && offsetof(Box3, hi) == 3 * sizeof(double));
inline bool ray_box_entry(const BvhRayTraversal::Slabs& s, const Box3& box, double t0, double t1, double& entry) noexcept {
  const auto b = std::bit_cast<std::array<double, 6>>(box);
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t near_face = s.enters_at_hi[k] ? k + 3 : k;
    const std::size_t far_face = s.enters_at_hi[k] ? k : k + 3;
    ray_box_axis<double>(b[near_face], b[far_face], s.origin[k], s.inverse_direction[k], t0, t1);
  }
  entry = t0;
  return t0 <= t1;
}

// The walk's per-ray state from the slabs: the rows of BvhNode::bounds holding each axis's near and far face.
inline void set_walk_ray(detail::BvhWalk& w, const BvhRayTraversal::Slabs& s) noexcept {
  for (std::size_t k = 0; k < 3; ++k) {
    w.origin[k] = s.origin[k];
    w.inverse_direction[k] = s.inverse_direction[k];
    w.near_face[k] = static_cast<std::uint8_t>(s.enters_at_hi[k] ? k + 3 : k);
    w.far_face[k] = static_cast<std::uint8_t>(s.enters_at_hi[k] ? k : k + 3);
  }
}

// The lanes of ray_box_entries8 in the translation unit's register width: one Lanes8 (a zmm) with AVX-512, two
// Lanes4 (ymm) with AVX2, four Lanes2 (xmm) otherwise. GCC 12 turns a comparison of a vector wider than the
// registers into one scalar comparison per lane (about 500 instructions per node with AVX2 when the walk ran
// Lanes8 there, counted by callgrind), not into pairs of vector ones. Internal linkage, as ray_box_entries8's:
// each translation unit has its own.
namespace node_lanes {
#if defined(__AVX512F__)
constexpr int width = 8;
using Lanes = detail::Lanes8;
using Row = float __attribute__((vector_size(8 * sizeof(float))));
[[gnu::always_inline]] static inline Lanes widen(const float* p) noexcept {  // exact: binary32 → binary64
  Row r;
  std::memcpy(&r, p, sizeof r);
  return __builtin_convertvector(r, Lanes);
}
[[gnu::always_inline]] static inline unsigned met_bits(Lanes t0, Lanes t1) noexcept {
  return static_cast<unsigned>(_mm512_cmp_pd_mask(reinterpret_cast<__m512d>(t0), reinterpret_cast<__m512d>(t1), _CMP_LE_OQ));
}
#elif defined(__AVX__)
constexpr int width = 4;
using Lanes = detail::Lanes4;
[[gnu::always_inline]] static inline Lanes widen(const float* p) noexcept {  // (__builtin_convertvector: two halves)
  return reinterpret_cast<Lanes>(_mm256_cvtps_pd(_mm_loadu_ps(p)));
}
[[gnu::always_inline]] static inline unsigned met_bits(Lanes t0, Lanes t1) noexcept {
  return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(t0 <= t1)));
}
#else
constexpr int width = 2;
using Lanes = detail::Lanes2;
using Row = float __attribute__((vector_size(2 * sizeof(float))));
[[gnu::always_inline]] static inline Lanes widen(const float* p) noexcept {
  Row r;
  std::memcpy(&r, p, sizeof r);
  return __builtin_convertvector(r, Lanes);
}
[[gnu::always_inline]] static inline unsigned met_bits(Lanes t0, Lanes t1) noexcept {
  const detail::Mask2 met = t0 <= t1;
  return static_cast<unsigned>(met[0] & 1) | static_cast<unsigned>(met[1] & 1) << 1;
}
#endif
}  // namespace node_lanes

// The eight children of `node` at once: each lane converts its child's binary32 bounds to double (exactly) and
// performs the test above — the same operations in the same order whatever the lanes' width (node_lanes).
// Slots beyond node.children() are not masked off: their empty boxes are rejected unless every axis was left
// out of the test, so the caller skips an accepted empty slot (BvhNode::empty_slot; it reads first and count of
// each accepted slot anyway). A stored box contains the exact one (lo rounded down, hi up), so a t in the exact
// box's slab is in the stored box's (RayBox.v, `slab_sound_outward`), and the test never rejects a child the
// exact ray meets. Bit s of the result: child s may be met; entries[s] is then its entry bound. Internal
// linkage: the body depends on the instruction set of the translation unit (bvh_walk_<isa>.cpp).
[[gnu::always_inline]] static inline unsigned ray_box_entries8(const detail::BvhWalk& w, const BvhNode& node,
                                                               double t_min, double t_max,
                                                               detail::Lanes8& entries) noexcept {
  using V = node_lanes::Lanes;
  constexpr int width = node_lanes::width;
  static_assert(BvhNode::width == 8 && sizeof(node.bounds[0]) == 8 * sizeof(float));
  unsigned bits = 0;
  for (int part = 0; part < 8 / width; ++part) {
    const auto row = [&](std::size_t face) { return node_lanes::widen(node.bounds[face].data() + part * width); };
    V t0 = detail::broadcast<V>(t_min), t1 = detail::broadcast<V>(t_max);
    for (std::size_t k = 0; k < 3; ++k)
      ray_box_axis<V>(row(w.near_face[k]), row(w.far_face[k]), detail::broadcast<V>(w.origin[k]),
                      detail::broadcast<V>(w.inverse_direction[k]), t0, t1);
    std::memcpy(reinterpret_cast<double*>(&entries) + part * width, &t0, sizeof t0);
    bits |= node_lanes::met_bits(t0, t1) << (part * width);
  }
  return bits;
}

}  // namespace raykernel::mesh_detail
