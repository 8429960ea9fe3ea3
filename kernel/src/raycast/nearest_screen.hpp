// The screen of nearest_hit: stage 1 of the relation for four or eight planes of a PlaneSet at once, and a
// lane-wise filter comparison of their t with the best hit so far, so that only the planes the scalar path
// must look at reach it (raycast/nearest_hit.cpp): those whose relation stage 1 cannot decide, and the hits
// not certainly farther than the best.
//
// Every lane computes the scalar routines' operations on its plane (lanes.hpp): dot3_rounded and
// dot3_filter_lanes (certified/dot3_filter.hpp) for den and num, filter_enclosure and
// compare_quotients_filter_lanes (certified/compare_quotients.hpp) for the comparison, so the stage-1 values
// handed to the scalar path are the bits it would have computed itself, and every decision is one the
// proofs cover (proofs/Filter.v `den_filter_lanes_sound`, `num_filter_lanes_sound`; proofs/CompareQuotients.v
// `compare_quotients_filter_sound`).
//
// Why skipping is exact: the best so far only ever changes to a plane with a strictly smaller exact t, so a
// hit whose t is certainly greater than the best's at the start of its group is greater than every later
// best and would never have won; a hit with an equal t is never "certainly greater" (the filter certifies
// only Δ ≠ 0), so the tie rule (the smaller index wins) stays with the scalar comparison, which sees the
// examined planes in ascending order.
//
// Compiled once per instruction set like the batch loop (batch/fast_loop.hpp): nearest_screen_avx2.cpp
// (-march=x86-64-v3, Lanes4), nearest_screen_portable.cpp (any target, Lanes2); nearest_hit.cpp picks one on
// first use.
#pragma once

#include "certified/compare_quotients.hpp"
#include "certified/dot3_filter.hpp"
#include "certified/lanes.hpp"
#include "certified/sign.hpp"
#include "ray_plane_formula.hpp"

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace raykernel::nearest_kernel {

// The widest lane type any screen uses; the columns are padded to a multiple of it.
inline constexpr std::size_t max_width = 8;

// A PlaneSet's candidate planes, structure of arrays: column c (point x, y, z, normal x, y, z) of candidate j
// at columns[c * stride + j]; stride = count rounded up to a multiple of max_width, the padding zeros (never
// read as a plane: the screen masks lanes ≥ count).
struct PlaneColumns {
  const double* columns;
  std::size_t stride;
  std::size_t count;
};

// The best hit so far, as the screen compares against it.
struct BestSoFar {
  bool exists = false;
  bool at_origin = false;                // num = 0 exactly: t = 0, which no later plane can beat
  detail::RoundedEnclosure num{}, den{};  // its stage-1 enclosures (filter_enclosure)
  std::int64_t den_sign = 0;              // its den's exact sign, ±1
};

// Stage 1 of one group of planes, candidates [first, first + width): the scalar path reads the lanes whose
// bit is set in `examine`.
struct GroupStage1 {
  std::size_t first = 0;
  std::uint32_t examine = 0;
  std::uint32_t farther = 0;  // hits set aside as certainly farther than the best, summed over the calls
  double den_product[3][max_width], den_value[max_width], den_magnitude[max_width];
  double num_product[3][max_width], num_value[max_width], num_magnitude[max_width];
  std::int64_t den_sign[max_width], num_sign[max_width];  // stage-1 signs (Sign's values; 2 = uncertain)

  [[nodiscard]] detail::Dot3Rounded den(unsigned lane) const noexcept {
    return {{den_product[0][lane], den_product[1][lane], den_product[2][lane]}, den_value[lane], den_magnitude[lane]};
  }
  [[nodiscard]] detail::Dot3Rounded num(unsigned lane) const noexcept {
    return {{num_product[0][lane], num_product[1][lane], num_product[2][lane]}, num_value[lane], num_magnitude[lane]};
  }
};

// From candidate `begin` (a multiple of the screen's width), the groups of planes until one has a lane to
// examine: fills `out` with that group (out.first, out.examine, its stage-1 values) and returns the candidate
// after it; returns columns.count when no plane from `begin` on needs the scalar path (then `out.examine` is
// 0). out.farther grows by the hits set aside. o and d: the ray's origin and direction.
using ScreenFunction = std::size_t (*)(const PlaneColumns& columns, const double o[3], const double d[3],
                                       const BestSoFar& best, std::size_t begin, GroupStage1& out) noexcept;

template <class V>
[[gnu::always_inline]] inline V load(const double* x) noexcept {
  V v;
  std::memcpy(&v, x, sizeof v);
  return v;
}
template <class V>
[[gnu::always_inline]] inline void store(double* x, V v) noexcept {
  std::memcpy(x, &v, sizeof v);
}

// Bit i set where lane i of the mask is true (−1).
template <class M>
[[gnu::always_inline]] inline std::uint32_t lane_bits(M mask) noexcept {
  std::uint32_t bits = 0;
  for (unsigned i = 0; i < sizeof(M) / sizeof(std::int64_t); ++i) bits |= static_cast<std::uint32_t>(mask[i] & 1) << i;
  return bits;
}

template <class V>
[[gnu::always_inline]] inline std::size_t screen(const PlaneColumns& pc, const double o[3], const double d[3],
                                                 const BestSoFar& best, std::size_t begin, GroupStage1& out) noexcept {
  using Integer = detail::IntegerOf<V>;
  constexpr std::size_t w = detail::width_of<V>;
  static_assert(max_width % w == 0);
  const V origin[3] = {detail::broadcast<V>(o[0]), detail::broadcast<V>(o[1]), detail::broadcast<V>(o[2])};
  const V direction[3] = {detail::broadcast<V>(d[0]), detail::broadcast<V>(d[1]), detail::broadcast<V>(d[2])};
  const detail::RoundedEnclosureT<V> best_num{detail::broadcast<V>(best.num.value), detail::broadcast<V>(best.num.radius)};
  const detail::RoundedEnclosureT<V> best_den{detail::broadcast<V>(best.den.value), detail::broadcast<V>(best.den.radius)};
  const double* column = pc.columns;
  const std::size_t stride = pc.stride;
  std::uint32_t farther_count = 0;
  for (std::size_t first = begin; first < pc.count; first += w) {
    const V p[3] = {load<V>(column + first), load<V>(column + stride + first), load<V>(column + 2 * stride + first)};
    const V n[3] = {load<V>(column + 3 * stride + first), load<V>(column + 4 * stride + first),
                    load<V>(column + 5 * stride + first)};
    const V diff[3] = {p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]};
    const detail::Dot3RoundedT<V> den = detail::dot3_rounded(direction, n), num = detail::dot3_rounded(diff, n);
    const Integer den_filter = detail::dot3_filter_lanes(den, detail::bounds::filter_den_relative);
    const Integer num_filter = detail::dot3_filter_lanes(num, detail::bounds::filter_num_relative);
    const auto certain = detail::both(den_filter != detail::uncertain_lane, num_filter != detail::uncertain_lane);
    const auto certain_hit = detail::both(certain, detail::mask_not(detail::signs_say_behind(num_filter, den_filter)));
    auto farther = certain_hit;  // every certain hit (num ≠ 0: t > 0) is farther than a best at t = 0
    if (!best.exists) {
      farther = decltype(farther){};  // nothing to compare with
    } else if (!best.at_origin) {
      // sign(t_lane − t_best) = sign(Δ)·sign(den_lane)·sign(den_best), Δ by compare_quotients_filter.
      const Integer delta = detail::compare_quotients_filter_lanes(
          detail::filter_enclosure(num, detail::bounds::filter_num_relative),
          detail::filter_enclosure(den, detail::bounds::filter_den_relative), best_num, best_den);
      farther = detail::both(farther, delta * den_filter * best.den_sign == 1);
    }
    const std::uint32_t valid = pc.count - first >= w ? (1u << w) - 1 : (1u << (pc.count - first)) - 1;
    const std::uint32_t farther_bits = lane_bits(farther) & valid;
    const std::uint32_t examine = (lane_bits(detail::mask_not(certain)) | lane_bits(certain_hit)) & ~farther_bits & valid;
    farther_count += static_cast<std::uint32_t>(__builtin_popcount(farther_bits));
    if (examine == 0) continue;
    out.first = first;
    out.examine = examine;
    out.farther += farther_count;
    for (int i = 0; i < 3; ++i) {
      store(out.den_product[i], den.product[i]);
      store(out.num_product[i], num.product[i]);
    }
    store(out.den_value, den.value), store(out.den_magnitude, den.magnitude);
    store(out.num_value, num.value), store(out.num_magnitude, num.magnitude);
    std::memcpy(out.den_sign, &den_filter, sizeof den_filter);
    std::memcpy(out.num_sign, &num_filter, sizeof num_filter);
    return first + w;
  }
  out.examine = 0;
  out.farther += farther_count;
  return pc.count;
}

// One screen per instruction set (nearest_screen_<isa>.cpp).
namespace portable {
std::size_t screen(const PlaneColumns&, const double[3], const double[3], const BestSoFar&, std::size_t,
                   GroupStage1&) noexcept;
}
namespace avx2 {
std::size_t screen(const PlaneColumns&, const double[3], const double[3], const BestSoFar&, std::size_t,
                   GroupStage1&) noexcept;
}

#define RAYKERNEL_DEFINE_NEAREST_SCREEN(isa, lane_type)                                                          \
  std::size_t raykernel::nearest_kernel::isa::screen(const PlaneColumns& c, const double o[3], const double d[3], \
                                                     const BestSoFar& b, std::size_t begin, GroupStage1& out) noexcept { \
    return nearest_kernel::screen<lane_type>(c, o, d, b, begin, out);                                            \
  }

}  // namespace raykernel::nearest_kernel
