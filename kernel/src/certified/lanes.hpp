// Lanes: the number types the certified routines are written for, so that each routine is written once and
// runs both on one query (`double`) and on eight at a time (`Lanes8`, a GCC/clang vector of 8 doubles) in
// the batch API. Every operation on Lanes8 is the same IEEE-754 operation applied to each lane separately:
// + − × / are the vector extensions' lane-wise operations, `fma` is one correctly rounded fused
// multiply-add per lane, `abs` clears the sign bit. So each lane computes exactly the bits the scalar
// routine computes for that query, and the proofs (which model the scalar operations) cover every lane.
//
// Comparisons give `bool` for double and a mask (a vector of 64-bit integers, −1 for true) for Lanes8;
// `select`, `all_of` and the integer "sign lanes" below hide that difference.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

namespace raykernel::detail {

inline constexpr int lane_count = 8;
using Lanes8 = double __attribute__((vector_size(8 * sizeof(double))));
using Mask8 = std::int64_t __attribute__((vector_size(8 * sizeof(std::int64_t))));
using Bits8 = std::uint64_t __attribute__((vector_size(8 * sizeof(std::uint64_t))));

// The mask and integer types of a lane type: bool / std::int64_t for double, Mask8 for Lanes8.
template <class V>
struct LaneTypes;
template <>
struct LaneTypes<double> {
  using mask = bool;
  using integer = std::int64_t;
  using bits = std::uint64_t;
};
template <>
struct LaneTypes<Lanes8> {
  using mask = Mask8;
  using integer = Mask8;
  using bits = Bits8;
};
template <class V>
using MaskOf = typename LaneTypes<V>::mask;
template <class V>
using IntegerOf = typename LaneTypes<V>::integer;
template <class V>
using BitsOf = typename LaneTypes<V>::bits;

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

// ---- Lanes8 --------------------------------------------------------------------------------------------

[[gnu::always_inline]] inline Lanes8 broadcast(double x) noexcept { return Lanes8{} + x; }
[[gnu::always_inline]] inline Lanes8 fma(Lanes8 a, Lanes8 b, Lanes8 c) noexcept {
  Lanes8 r;
  for (int i = 0; i < lane_count; ++i) r[i] = __builtin_fma(a[i], b[i], c[i]);  // one vfmadd with FMA units
  return r;
}
[[gnu::always_inline]] inline Lanes8 abs(Lanes8 x) noexcept {
  return reinterpret_cast<Lanes8>(reinterpret_cast<Bits8>(x) & (Bits8{} + 0x7fffffffffffffffULL));
}
// Each lane takes a's bits where m is true (−1) and b's where it is false (0). Written with bitwise
// operations rather than `m ? a : b`: GCC 12 fails on the latter inside target_clones (an internal error).
[[gnu::always_inline]] inline Mask8 select(Mask8 m, Mask8 a, Mask8 b) noexcept { return (a & m) | (b & ~m); }
[[gnu::always_inline]] inline Lanes8 select(Mask8 m, Lanes8 a, Lanes8 b) noexcept {
  return reinterpret_cast<Lanes8>(select(m, reinterpret_cast<Mask8>(a), reinterpret_cast<Mask8>(b)));
}
// A mask (−1/0 per lane) as integers 1/0.
[[gnu::always_inline]] inline Mask8 to_integer(Mask8 m) noexcept { return -m; }
[[gnu::always_inline]] inline Mask8 both(Mask8 a, Mask8 b) noexcept { return a & b; }
[[gnu::always_inline]] inline Mask8 mask_not(Mask8 a) noexcept { return ~a; }
[[gnu::always_inline]] inline Bits8 to_bits(Lanes8 x) noexcept { return reinterpret_cast<Bits8>(x); }
[[gnu::always_inline]] inline Lanes8 from_bits(Bits8 b) noexcept { return reinterpret_cast<Lanes8>(b); }

}  // namespace raykernel::detail
