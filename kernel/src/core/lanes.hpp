// Lanes: the number types the certified routines are written for, so that each routine is written once and
// runs both on one value (`double`) and on two, four or eight at a time (`Lanes2`, `Lanes4`, `Lanes8`:
// GCC/clang vectors of doubles): den and num of one query side by side (`intersect`), or four or eight
// queries in the batch API. Every operation on Lanes8 is the same IEEE-754 operation applied to each lane separately:
// + − × / are the vector extensions' lane-wise operations, `fma` is one correctly rounded fused
// multiply-add per lane, `abs` clears the sign bit. So each lane computes exactly the bits the scalar
// routine computes for that query, and the proofs (which model the scalar operations) cover every lane.
//
// Comparisons give `bool` for double and a mask (a vector of 64-bit integers, −1 for true) for Lanes8;
// `select`, `any_lane` and the integer "sign lanes" (sign.hpp) hide that difference.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace raykernel::detail {

// Vectors of 2 doubles (one xmm), 4 doubles (AVX2: one ymm) and 8 doubles (AVX-512: one zmm), their
// comparison masks and their bit patterns. (Spelled out: GCC ignores a vector_size that depends on a template
// parameter.) A mask is the type a comparison of two vectors yields, whose element type differs between the
// compilers: `long` (std::int64_t) with GCC, `long long` with clang. Declared as that type, it is the one
// the overloads below and sign.hpp's are found for with either compiler.
using Lanes2 = double __attribute__((vector_size(2 * sizeof(double))));
using Lanes4 = double __attribute__((vector_size(4 * sizeof(double))));
using Lanes8 = double __attribute__((vector_size(8 * sizeof(double))));
using Mask2 = decltype(Lanes2{} < Lanes2{});
using Mask4 = decltype(Lanes4{} < Lanes4{});
using Mask8 = decltype(Lanes8{} < Lanes8{});
static_assert(sizeof(Mask2) == sizeof(Lanes2) && sizeof(Mask4) == sizeof(Lanes4) && sizeof(Mask8) == sizeof(Lanes8));
static_assert(sizeof(Mask4{}[0]) == sizeof(std::int64_t), "a mask has one 64-bit integer per lane");
using Bits2 = std::uint64_t __attribute__((vector_size(2 * sizeof(std::uint64_t))));
using Bits4 = std::uint64_t __attribute__((vector_size(4 * sizeof(std::uint64_t))));
using Bits8 = std::uint64_t __attribute__((vector_size(8 * sizeof(std::uint64_t))));

// The mask and integer types of a lane type: bool / std::int64_t for double, the mask vector for vectors.
template <class V>
struct LaneTypes;
template <>
struct LaneTypes<double> {
  using mask = bool;
  using integer = std::int64_t;
  using bits = std::uint64_t;
  static constexpr int width = 1;
};
template <>
struct LaneTypes<Lanes2> {
  using mask = Mask2;
  using integer = Mask2;
  using bits = Bits2;
  static constexpr int width = 2;
};
template <>
struct LaneTypes<Lanes4> {
  using mask = Mask4;
  using integer = Mask4;
  using bits = Bits4;
  static constexpr int width = 4;
};
template <>
struct LaneTypes<Lanes8> {
  using mask = Mask8;
  using integer = Mask8;
  using bits = Bits8;
  static constexpr int width = 8;
};
template <class V>
using MaskOf = typename LaneTypes<V>::mask;
template <class V>
using IntegerOf = typename LaneTypes<V>::integer;
template <class V>
using BitsOf = typename LaneTypes<V>::bits;
template <class V>
inline constexpr int width_of = LaneTypes<V>::width;

// ---- double --------------------------------------------------------------------------------------------

[[gnu::always_inline]] inline double fma(double a, double b, double c) noexcept { return std::fma(a, b, c); }
[[gnu::always_inline]] inline double abs(double x) noexcept { return std::fabs(x); }
[[gnu::always_inline]] inline double select(bool m, double a, double b) noexcept { return m ? a : b; }
[[gnu::always_inline]] inline std::int64_t select(bool m, std::int64_t a, std::int64_t b) noexcept {
  return m ? a : b;
}
[[gnu::always_inline]] inline std::int64_t to_integer(bool m) noexcept { return static_cast<std::int64_t>(m); }
[[gnu::always_inline]] inline std::uint64_t to_bits(double x) noexcept {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
[[gnu::always_inline]] inline double from_bits(std::uint64_t b) noexcept {
  double x;
  std::memcpy(&x, &b, sizeof x);
  return x;
}

// Both masks true; a mask negated (no branch).
[[gnu::always_inline]] inline bool both(bool a, bool b) noexcept { return static_cast<bool>(a & b); }
[[gnu::always_inline]] inline bool mask_not(bool a) noexcept { return !a; }
// Whether the mask is true (for a vector mask: in any lane).
[[gnu::always_inline]] inline bool any_lane(bool m) noexcept { return m; }

// ---- Lanes4, Lanes8 ---------------------------------------------------------------------------------------

#define RAYKERNEL_VECTOR_LANE_OPERATIONS(W)                                                                   \
  [[gnu::always_inline]] inline Lanes##W fma(Lanes##W a, Lanes##W b, Lanes##W c) noexcept {                   \
    Lanes##W r;                                                                                                \
    for (int i = 0; i < W; ++i) r[i] = __builtin_fma(a[i], b[i], c[i]); /* one vfmadd with FMA units */       \
    return r;                                                                                                  \
  }                                                                                                            \
  [[gnu::always_inline]] inline Lanes##W abs(Lanes##W x) noexcept {                                          \
    return reinterpret_cast<Lanes##W>(reinterpret_cast<Bits##W>(x) & (Bits##W{} + 0x7fffffffffffffffULL));    \
  }                                                                                                            \
  /* Each lane takes a's bits where m is true (−1) and b's where it is false (0); bitwise rather than       */ \
  /* `m ? a : b`, which GCC 12 fails on inside target_clones (an internal error).                            */ \
  [[gnu::always_inline]] inline Mask##W select(Mask##W m, Mask##W a, Mask##W b) noexcept {                   \
    return (a & m) | (b & ~m);                                                                                 \
  }                                                                                                            \
  [[gnu::always_inline]] inline Lanes##W select(Mask##W m, Lanes##W a, Lanes##W b) noexcept {                \
    return reinterpret_cast<Lanes##W>(select(m, reinterpret_cast<Mask##W>(a), reinterpret_cast<Mask##W>(b))); \
  }                                                                                                            \
  /* A mask (−1/0 per lane) as integers 1/0. */                                                                \
  [[gnu::always_inline]] inline Mask##W to_integer(Mask##W m) noexcept { return -m; }                        \
  [[gnu::always_inline]] inline Mask##W both(Mask##W a, Mask##W b) noexcept { return a & b; }                \
  [[gnu::always_inline]] inline Mask##W mask_not(Mask##W a) noexcept { return ~a; }                          \
  [[gnu::always_inline]] inline Bits##W to_bits(Lanes##W x) noexcept { return reinterpret_cast<Bits##W>(x); } \
  [[gnu::always_inline]] inline Lanes##W from_bits(Bits##W b) noexcept { return reinterpret_cast<Lanes##W>(b); }

RAYKERNEL_VECTOR_LANE_OPERATIONS(2)
RAYKERNEL_VECTOR_LANE_OPERATIONS(4)
RAYKERNEL_VECTOR_LANE_OPERATIONS(8)
#undef RAYKERNEL_VECTOR_LANE_OPERATIONS

// Whether any lane of a comparison's mask is true.
template <class M>
  requires(sizeof(M) > sizeof(std::int64_t))
[[nodiscard]] [[gnu::always_inline]] inline bool any_lane(M m) noexcept {
  auto r = m[0];
  for (int i = 1; i < static_cast<int>(sizeof(M) / sizeof(m[0])); ++i) r |= m[i];
  return r != 0;
}

// A lane type filled with one value.
template <class V>
[[gnu::always_inline]] inline V broadcast(double x) noexcept {
  return V{} + x;
}

}  // namespace raykernel::detail
