// The exact sign of a 3×3 determinant x·(y × z) of nine doubles in fixed-width integers, and its value as an exact
// expansion of at most four doubles: stage 3's first try for the ray–triangle determinants, whose leaves are
// doubles or differences p − o of doubles (each the exact sum of TwoDiff's two parts), without products of
// expansions and without a rounding.
//
// Each vector's components are read as integers over one power of two (integer_vector, integer_vector_sum): a
// finite double is ±m·2^e; with m's trailing zeros stripped and E the least exponent of the vector's nonzero
// doubles, every double is the integer ±m·2^(e − E), and a component the sum of its parts' integers X_i. When
// every |X_i| < 2^62 (so a ray–triangle query whose doubles' exponents span less than about 9 bits beyond their
// significands: any grid of coordinates, a vertex or an origin an ulp off), the cross product Y × Z is computed
// exactly in signed 128-bit integers (each component below 2^125) and the determinant D = X·(Y × Z) in signed
// 192-bit two's complement (below 2^189: no wrap); x·(y × z) = D·2^(Ex + Ey + Ez), so its sign is D's.
//
//   Valid range: any doubles; `uncertain` when a part is not finite or an aligned part or a component reaches 2^62
//                (the caller goes on to the expansions, then the exact stage).
//   Error bound: none: integer arithmetic, no floating-point operation (nothing depends on the rounding mode,
//                FTZ/DAZ or traps, and no flag is raised).
//   Certified by: proofs/core/IntegerDet3.v, `integer_det3_sign_correct` (integer_vector's integers have the
//                doubles' values, the determinant's sign is its integer's, and the 128- and 192-bit ranges hold),
//                `integer_vector_sum_value` (integer_vector_sum's integers have the sums' values);
//                the limb arithmetic is compared with the model's Z arithmetic by the twin runner.
#pragma once

#include "core/expansion.hpp"
#include "core/sign.hpp"

#include <bit>
#include <cstdint>

namespace raykernel::detail {

__extension__ typedef __int128 Int128;            // GCC and clang (`__extension__`: -Wpedantic)
__extension__ typedef unsigned __int128 UInt128;

// N doubles as integers over one power of two: a finite double is ±m·2^e (m odd: its significand with the
// trailing zeros stripped); E is the least exponent of the nonzero ones, and each is the integer ±m·2^(e − E).
// Not ok when a double is not finite or an integer reaches 2^bits. (Modelled in proofs/core/IntegerDet3.v by
// component, least_exponent and aligned: integer_vector reads three doubles, integer_vector_sum six.)
template <std::size_t N>
struct IntegerReading {
  std::int64_t v[N];
  int exponent;  // E: x_k = v_k·2^E (0 when every x_k is 0)
  bool ok;
};

// Branch-free (masks and conditional moves): which double is zero, which exponent is least and which integer is too
// wide depend on the data, and a mispredicted branch here cost more than the reading (measured, bench/README.md).
template <std::size_t N>
[[nodiscard]] [[gnu::always_inline]] inline IntegerReading<N> integer_read(const double (&x)[N], int bits) noexcept {
  constexpr int none = 1 << 20;  // the least exponent of no nonzero double
  std::uint64_t m[N];
  int e[N];
  std::uint64_t negative[N];  // 1 or 0
  bool finite = true;
  int least = none;
  for (std::size_t k = 0; k < N; ++k) {
    const std::uint64_t b = std::bit_cast<std::uint64_t>(x[k]);
    const int field = static_cast<int>((b >> 52) & 0x7ff);
    const std::uint64_t significand = (b & ((std::uint64_t{1} << 52) - 1)) | (static_cast<std::uint64_t>(field != 0) << 52);
    // significand < 2^53: the top bit added makes the count that of significand's trailing zeros when it is
    // nonzero, and 63 (m = 0) when it is 0, without a branch or a shift by 64.
    const int zeros = std::countr_zero(significand | (std::uint64_t{1} << 63));
    m[k] = significand >> zeros;                                     // odd, or 0
    e[k] = field + static_cast<int>(field == 0) - 1075 + zeros;     // |x_k| = m·2^e (field 0: the exponent of 1)
    negative[k] = b >> 63;
    finite = finite & (field != 0x7ff);
    const int candidate = m[k] != 0 ? e[k] : none;
    least = candidate < least ? candidate : least;
  }
  IntegerReading<N> r;
  r.exponent = least == none ? 0 : least;
  bool ok = finite;
  for (std::size_t k = 0; k < N; ++k) {
    const int shift = m[k] != 0 ? e[k] - least : 0;  // ≥ 0 (a zero double reads as 0 whatever its exponent)
    const int width = 64 - std::countl_zero(m[k]);   // m < 2^width (0 for m = 0)
    const bool fits = shift + width <= bits;         // the integer m·2^shift < 2^bits (bits ≤ 63)
    ok = ok & fits;
    const std::int64_t value = static_cast<std::int64_t>(m[k] << (fits ? shift : 0)) & -static_cast<std::int64_t>(fits);
    const std::int64_t sign = -static_cast<std::int64_t>(negative[k]);  // 0 or −1
    r.v[k] = (value ^ sign) - sign;                                       // ±value
  }
  r.ok = ok;
  return r;
}

// A vector of three doubles as integers over one power of two (see above); `ok` false when a component is not
// finite or an integer reaches 2^62.
struct IntegerVector {
  std::int64_t v[3];
  int exponent;  // E: x_i = v_i·2^E (0 when every component is 0)
  bool ok;
};

[[nodiscard]] [[gnu::always_inline]] inline IntegerVector integer_vector(const double x[3]) noexcept {
  const double c[3] = {x[0], x[1], x[2]};
  const IntegerReading<3> r = integer_read(c, 62);
  return {{r.v[0], r.v[1], r.v[2]}, r.exponent, r.ok};
}

// A vector whose components are exact sums of two doubles, x_i = h_i + l_i (a difference p − o as TwoDiff's high
// and low parts, exact even when p − o is not a double): the six doubles read together (integer_read, each below
// 2^62), X_i = H_i + L_i, `ok` false also when a sum reaches 2^62 (a sum of two integers below 2^62 is below 2^63:
// int64 holds it).
[[nodiscard]] [[gnu::always_inline]] inline IntegerVector integer_vector_sum(const double (&part)[6]) noexcept {
  // Zero low parts (p − o a double, as on any grid) take no part in E and read as 0: the high parts alone give the
  // same integers (±0 by their bits, whatever the floating-point environment).
  const std::uint64_t low_bits = (std::bit_cast<std::uint64_t>(part[3]) | std::bit_cast<std::uint64_t>(part[4]) |
                                  std::bit_cast<std::uint64_t>(part[5])) << 1;
  if (low_bits == 0) [[likely]]
    return integer_vector(part);
  const IntegerReading<6> r = integer_read(part, 62);
  IntegerVector v{{0, 0, 0}, r.exponent, r.ok};
  for (int i = 0; i < 3; ++i) {
    v.v[i] = r.v[i] + r.v[i + 3];
    if (v.v[i] <= -(std::int64_t{1} << 62) || v.v[i] >= (std::int64_t{1} << 62)) v.ok = false;
  }
  return v;
}

// D = X·(Y × Z) of three vectors read by integer_vector, in 192-bit two's complement (w[2]:w[1]:w[0]), the cross
// product as ray_triangle_formula.hpp's cross_terms writes it. Valid when the three are ok.
struct Int192 {
  std::uint64_t w[3];
};

[[nodiscard]] [[gnu::always_inline]] inline Int192 integer_det3(const IntegerVector& X, const IntegerVector& Y,
                                                                const IntegerVector& Z) noexcept {
  // (Y × Z)_i = Y_j Z_k − Y_k Z_j, (i, j, k) = (0, 1, 2), (1, 2, 0), (2, 0, 1): each product below 2^124.
  const Int128 c[3] = {static_cast<Int128>(Y.v[1]) * Z.v[2] - static_cast<Int128>(Y.v[2]) * Z.v[1],
                       static_cast<Int128>(Y.v[2]) * Z.v[0] - static_cast<Int128>(Y.v[0]) * Z.v[2],
                       static_cast<Int128>(Y.v[0]) * Z.v[1] - static_cast<Int128>(Y.v[1]) * Z.v[0]};
  // Σ X_i c_i in 192-bit two's complement (s2:s1:s0): with c_i = hi·2^64 + lo (hi signed, lo unsigned),
  // X_i c_i = (X_i·hi)·2^64 + X_i·lo, each product exact in 128 bits, sign-extended to 192.
  std::uint64_t s0 = 0, s1 = 0, s2 = 0;
  for (int i = 0; i < 3; ++i) {
    const std::uint64_t lo = static_cast<std::uint64_t>(c[i]);
    const std::int64_t hi = static_cast<std::int64_t>(c[i] >> 64);
    const Int128 low_part = static_cast<Int128>(X.v[i]) * static_cast<Int128>(lo);  // |·| < 2^126
    const Int128 high_part = static_cast<Int128>(X.v[i]) * hi;                       // |·| < 2^125
    // (s2:s1:s0) += low_part (sign-extended), then += high_part·2^64 (sign-extended).
    const UInt128 a = static_cast<UInt128>(s0) + static_cast<std::uint64_t>(low_part);
    s0 = static_cast<std::uint64_t>(a);
    const UInt128 b = static_cast<UInt128>(s1) + static_cast<std::uint64_t>(static_cast<UInt128>(low_part) >> 64) +
                      static_cast<std::uint64_t>(high_part) + static_cast<std::uint64_t>(a >> 64);
    s1 = static_cast<std::uint64_t>(b);
    s2 += static_cast<std::uint64_t>(low_part < 0 ? -1 : 0) + static_cast<std::uint64_t>(high_part >> 64) +
          static_cast<std::uint64_t>(b >> 64);
  }
  return {{s0, s1, s2}};
}

[[nodiscard]] inline Sign sign(const Int192& D) noexcept {
  if (static_cast<std::int64_t>(D.w[2]) < 0) return Sign::negative;
  return (D.w[0] | D.w[1] | D.w[2]) != 0 ? Sign::positive : Sign::zero;
}

// sign(X·(Y × Z)) of three vectors read by integer_vector (each over its own power of two, which the sign does not
// see); `uncertain` when a vector is not ok. (A caller that signs several determinants of the same vectors reads
// each vector once.)
[[nodiscard]] inline Sign integer_det3_sign(const IntegerVector& X, const IntegerVector& Y, const IntegerVector& Z) noexcept {
  if (!(X.ok & Y.ok & Z.ok)) return Sign::uncertain;
  return sign(integer_det3(X, Y, Z));
}

// ±c·2^q as a double, built from its bits (integer operations only: no rounding, no flag, whatever the
// floating-point environment). Valid range: 0 < c < 2^53, −1074 ≤ q ≤ 971 (then c·2^q is a double: normal when
// its leading bit's exponent is at least −1022, else subnormal with fraction c·2^(q + 1074) < 2^52).
[[nodiscard]] inline double dyadic_double(bool negative, std::uint64_t c, int q) noexcept {
  const int width = 64 - std::countl_zero(c);  // c < 2^width, 1 ≤ width ≤ 53
  const int top = q + width - 1;               // the exponent of c·2^q's leading bit, ≤ 1023
  const std::uint64_t magnitude =
      top >= -1022 ? (static_cast<std::uint64_t>(top + 1023) << 52) | ((c << (53 - width)) & ((std::uint64_t{1} << 52) - 1))
                   : c << (q + 1074);
  return std::bit_cast<double>(magnitude | (negative ? std::uint64_t{1} << 63 : 0));
}

// x·(y × z) = D·2^(Ex + Ey + Ez) as a short exact expansion: |D| in chunks of 53 bits, c_k = ⌊|D|/2^(53k)⌋ mod 2^53
// (k = 0..3: |D| < 2^189), each nonzero chunk the double ±c_k·2^(E + 53k), in increasing order; the zero
// determinant is {0}. False (`out` then unspecified) when a vector is not ok or a nonzero chunk's exponent lies outside
// [−1074, 971] (the caller goes on to the expansions of doubles).
//   Error bound: none: the components sum exactly to the determinant (integer arithmetic and exact doubles).
//   Certified by: proofs/core/IntegerExpansion.v, `integer_components_sound` (at most four finite doubles whose
//   exact sum is D·2^E), with proofs/core/IntegerDet3.v, `det3_scaled` and `det3_range`; compared with the twin
//   through the cascade's roundings (TriangleCascadeFlowTwins.v, routine tri_cascade_intersect).
template <std::size_t K>
  requires(K >= 4)
[[nodiscard]] inline bool integer_det3_components(const IntegerVector& X, const IntegerVector& Y, const IntegerVector& Z,
                                                  Expansion<K>& out) noexcept {
  if (!(X.ok & Y.ok & Z.ok)) return false;
  const Int192 D = integer_det3(X, Y, Z);
  const bool negative = static_cast<std::int64_t>(D.w[2]) < 0;
  // |D|: two's complement negation when negative (complement under a mask, plus one; no branch on the sign).
  const std::uint64_t flip = -static_cast<std::uint64_t>(negative);  // all ones, or 0
  std::uint64_t m[3];
  const UInt128 a = static_cast<UInt128>(D.w[0] ^ flip) + (flip & 1);
  const UInt128 b = static_cast<UInt128>(D.w[1] ^ flip) + static_cast<std::uint64_t>(a >> 64);
  m[0] = static_cast<std::uint64_t>(a);
  m[1] = static_cast<std::uint64_t>(b);
  m[2] = (D.w[2] ^ flip) + static_cast<std::uint64_t>(b >> 64);
  const int E = X.exponent + Y.exponent + Z.exponent;
  constexpr std::uint64_t chunk_mask = (std::uint64_t{1} << 53) - 1;
  std::size_t size = 0;
  for (int k = 0; k < 4; ++k) {
    const int start = 53 * k, word = start / 64, offset = start % 64;
    UInt128 window = m[word];
    if (word + 1 < 3) window |= static_cast<UInt128>(m[word + 1]) << 64;
    const std::uint64_t c = static_cast<std::uint64_t>(window >> offset) & chunk_mask;
    if (c == 0) continue;
    const int q = E + start;
    if (q < -1074 || q > 971) return false;
    out.component[size++] = dyadic_double(negative, c, q);
  }
  if (size == 0) out.component[size++] = 0.0;
  out.size = size;
  return true;
}

// sign(x·(y × z)) of nine doubles; `uncertain` outside the valid range above.
[[nodiscard]] inline Sign integer_det3_sign(const double x[3], const double y[3], const double z[3]) noexcept {
  return integer_det3_sign(integer_vector(x), integer_vector(y), integer_vector(z));
}

}  // namespace raykernel::detail
