// The screen of nearest_hit: stage 1 of the relation for four (AVX2) or two planes of a PlaneSet at once, and
// a lane-wise filter comparison of their t with the t of one reference plane the ray hits, so that only the
// planes the scalar path must look at reach it (nearest/nearest_hit.cpp): those whose relation stage 1
// cannot decide, and the hits not certainly farther than the reference.
//
// Every lane computes the scalar routines' operations on its plane (lanes.hpp): dot3_rounded and
// dot3_filter_lanes (core/dot3_filter.hpp) for den and num, filter_enclosure and
// compare_quotients_filter_lanes (nearest/compare_quotients.hpp) for the comparison, so the stage-1 values
// handed to the scalar path are the bits it would have computed itself, and every decision is one the
// proofs cover (proofs/plane/PlaneFilter.v `den_filter_lanes_sound`, `num_filter_lanes_sound`;
// proofs/compare/CompareQuotients.v `compare_quotients_filter_sound`).
//
// Why skipping is exact: the reference R is a plane the ray hits, so the winner's exact t is at most t_R; a
// hit whose t is certainly greater than t_R is neither the winner nor tied with it. The planes left are
// examined by the scalar path in ascending index order, the winner and every plane tied with it among them
// (an equal t is never "certainly greater": the filter certifies only Δ ≠ 0), so the sequential minimum over
// them, ties to the smaller index, is the answer over all planes. R is chosen by the smallest rounded
// quotient num ⊘ den among the planes stage 1 certifies as hits: a heuristic that decides nothing (any hit
// would be correct; the nearer, the more planes are set aside), which makes the screen independent of the
// planes' order (parallel layers listed from far to near, as in the demo64 benchmark, would otherwise
// change the best at every plane).
//
// Compiled once per instruction set like the batch loop (plane/fast_loop.hpp): nearest_screen_avx2.cpp
// (-march=x86-64-v3, Lanes4), nearest_screen_portable.cpp (any target, Lanes2); nearest_hit.cpp picks one on
// first use.
#pragma once

#include "nearest/compare_quotients.hpp"
#include "core/dot3_filter.hpp"
#include "core/lanes.hpp"
#include "core/sign.hpp"
#include "plane/ray_plane_formula.hpp"

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

// The reference plane, as the screen compares against it.
struct Reference {
  bool exists = false;                    // false: no plane is a certain hit, every hit is examined
  detail::RoundedEnclosure num{}, den{};  // its stage-1 enclosures (filter_enclosure)
  std::int64_t den_sign = 0;              // its den's exact sign, ±1 (certified by stage 1)
};

// Stage 1 of one group of planes, candidates [first, first + width): the scalar path reads the lanes whose
// bit is set in `examine`.
struct GroupStage1 {
  std::size_t first = 0;
  std::uint32_t examine = 0;
  std::uint32_t farther = 0;  // hits set aside as certainly farther than the reference, summed over the calls
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

// A screen: `reference` picks the plane the others are compared with (see `reference` below); `screen`, from
// candidate `begin` (a multiple of the screen's width), goes through the groups of planes until one has a
// lane to examine, fills `out` with that group (out.first, out.examine, its stage-1 values) and returns the
// candidate after it; it returns columns.count when no plane from `begin` on needs the scalar path (then
// `out.examine` is 0). out.farther grows by the hits set aside. o and d: the ray's origin and direction.
struct ScreenFunctions {
  Reference (*reference)(const PlaneColumns& columns, const double o[3], const double d[3]) noexcept;
  std::size_t (*screen)(const PlaneColumns& columns, const double o[3], const double d[3], const Reference& best,
                        std::size_t begin, GroupStage1& out) noexcept;
};
using ScreenFunction = const ScreenFunctions*;

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

// Stage 1 of the group of planes [first, first + width(V)).
template <class V>
struct GroupValues {
  detail::Dot3RoundedT<V> den, num;
  detail::IntegerOf<V> den_filter, num_filter;
};
template <class V>
[[gnu::always_inline]] inline GroupValues<V> group_values(const PlaneColumns& pc, const V origin[3], const V direction[3],
                                                         std::size_t first) noexcept {
  const double* column = pc.columns + first;
  const std::size_t stride = pc.stride;
  const V p[3] = {load<V>(column), load<V>(column + stride), load<V>(column + 2 * stride)};
  const V n[3] = {load<V>(column + 3 * stride), load<V>(column + 4 * stride), load<V>(column + 5 * stride)};
  const V diff[3] = {p[0] - origin[0], p[1] - origin[1], p[2] - origin[2]};
  GroupValues<V> g{detail::dot3_rounded(direction, n), detail::dot3_rounded(diff, n), {}, {}};
  g.den_filter = detail::dot3_filter_lanes(g.den, detail::bounds::filter_den_relative);
  g.num_filter = detail::dot3_filter_lanes(g.num, detail::bounds::filter_num_relative);
  return g;
}

// Lanes whose relation stage 1 certifies as hit (num and den certain, same sign; never num = 0).
template <class V>
[[gnu::always_inline]] inline auto certain_hit_lanes(const GroupValues<V>& g) noexcept {
  const auto certain = detail::both(g.den_filter != detail::uncertain_lane, g.num_filter != detail::uncertain_lane);
  return detail::both(certain, detail::mask_not(detail::signs_say_behind(g.num_filter, g.den_filter)));
}

// The reference plane of a ray: among the planes stage 1 certifies as hit, one whose rounded quotient
// num ⊘ den is smallest (a heuristic choice, never a decision: any certain hit would do, the nearer the
// better); `exists` false when no plane is a certain hit.
template <class V>
[[gnu::always_inline]] inline Reference reference(const PlaneColumns& pc, const double o[3], const double d[3]) noexcept {
  constexpr std::size_t w = detail::width_of<V>;
  const V origin[3] = {detail::broadcast<V>(o[0]), detail::broadcast<V>(o[1]), detail::broadcast<V>(o[2])};
  const V direction[3] = {detail::broadcast<V>(d[0]), detail::broadcast<V>(d[1]), detail::broadcast<V>(d[2])};
  const V infinity = detail::broadcast<V>(__builtin_inf());
  V nearest = infinity;
  V where = detail::broadcast<V>(-1.0);  // candidate index (exact in a double)
  V lane_index;
  for (std::size_t i = 0; i < w; ++i) lane_index[i] = static_cast<double>(i);
  for (std::size_t first = 0; first < pc.count; first += w) {
    const GroupValues<V> g = group_values(pc, origin, direction, first);
    const auto valid = lane_index + static_cast<double>(first) < static_cast<double>(pc.count);
    const V t = detail::select(detail::both(certain_hit_lanes(g), valid), g.num.value / g.den.value, infinity);
    const auto nearer = t < nearest;
    nearest = detail::select(nearer, t, nearest);
    where = detail::select(nearer, lane_index + static_cast<double>(first), where);
  }
  double t_min = __builtin_inf(), index = -1;
  for (std::size_t i = 0; i < w; ++i)
    if (nearest[i] < t_min) t_min = nearest[i], index = where[i];
  Reference best;
  if (index < 0) return best;
  const std::size_t j = static_cast<std::size_t>(index);
  const std::size_t stride = pc.stride;
  const double* column = pc.columns + j;
  const double n[3] = {column[3 * stride], column[4 * stride], column[5 * stride]};
  const double diff[3] = {column[0] - o[0], column[stride] - o[1], column[2 * stride] - o[2]};
  const detail::Dot3Rounded den = detail::dot3_rounded(d, n), num = detail::dot3_rounded(diff, n);
  best.exists = true;
  best.num = detail::filter_enclosure(num, detail::bounds::filter_num_relative);
  best.den = detail::filter_enclosure(den, detail::bounds::filter_den_relative);
  best.den_sign = detail::dot3_filter_lanes(den, detail::bounds::filter_den_relative);
  return best;
}

template <class V>
[[gnu::always_inline]] inline std::size_t screen(const PlaneColumns& pc, const double o[3], const double d[3],
                                                 const Reference& best, std::size_t begin, GroupStage1& out) noexcept {
  using Integer = detail::IntegerOf<V>;
  constexpr std::size_t w = detail::width_of<V>;
  static_assert(max_width % w == 0);
  const V origin[3] = {detail::broadcast<V>(o[0]), detail::broadcast<V>(o[1]), detail::broadcast<V>(o[2])};
  const V direction[3] = {detail::broadcast<V>(d[0]), detail::broadcast<V>(d[1]), detail::broadcast<V>(d[2])};
  const detail::RoundedEnclosureT<V> best_num{detail::broadcast<V>(best.num.value), detail::broadcast<V>(best.num.radius)};
  const detail::RoundedEnclosureT<V> best_den{detail::broadcast<V>(best.den.value), detail::broadcast<V>(best.den.radius)};
  std::uint32_t farther_count = 0;
  for (std::size_t first = begin; first < pc.count; first += w) {
    const GroupValues<V> g = group_values(pc, origin, direction, first);
    const auto certain = detail::both(g.den_filter != detail::uncertain_lane, g.num_filter != detail::uncertain_lane);
    const auto certain_hit = certain_hit_lanes(g);
    auto farther = certain_hit;
    if (!best.exists) {
      farther = decltype(farther){};  // nothing to compare with
    } else {
      // sign(t_lane − t_R) = sign(Δ)·sign(den_lane)·sign(den_R), Δ by compare_quotients_filter.
      const Integer delta = detail::compare_quotients_filter_lanes(
          detail::filter_enclosure(g.num, detail::bounds::filter_num_relative),
          detail::filter_enclosure(g.den, detail::bounds::filter_den_relative), best_num, best_den);
      farther = detail::both(farther, delta * g.den_filter * best.den_sign == 1);
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
      store(out.den_product[i], g.den.product[i]);
      store(out.num_product[i], g.num.product[i]);
    }
    store(out.den_value, g.den.value), store(out.den_magnitude, g.den.magnitude);
    store(out.num_value, g.num.value), store(out.num_magnitude, g.num.magnitude);
    std::memcpy(out.den_sign, &g.den_filter, sizeof g.den_filter);
    std::memcpy(out.num_sign, &g.num_filter, sizeof g.num_filter);
    return first + w;
  }
  out.examine = 0;
  out.farther += farther_count;
  return pc.count;
}

// One screen per instruction set (nearest_screen_<isa>.cpp).
#define RAYKERNEL_DECLARE_NEAREST_SCREEN(isa)                                                                  \
  namespace isa {                                                                                             \
  Reference reference(const PlaneColumns&, const double[3], const double[3]) noexcept;                        \
  std::size_t screen(const PlaneColumns&, const double[3], const double[3], const Reference&, std::size_t,    \
                     GroupStage1&) noexcept;                                                                  \
  }
RAYKERNEL_DECLARE_NEAREST_SCREEN(portable)
RAYKERNEL_DECLARE_NEAREST_SCREEN(avx2)
#undef RAYKERNEL_DECLARE_NEAREST_SCREEN

#define RAYKERNEL_DEFINE_NEAREST_SCREEN(isa, lane_type)                                                          \
  raykernel::nearest_kernel::Reference raykernel::nearest_kernel::isa::reference(                               \
      const PlaneColumns& c, const double o[3], const double d[3]) noexcept {                                   \
    return nearest_kernel::reference<lane_type>(c, o, d);                                                        \
  }                                                                                                              \
  std::size_t raykernel::nearest_kernel::isa::screen(const PlaneColumns& c, const double o[3], const double d[3], \
                                                     const Reference& b, std::size_t begin, GroupStage1& out) noexcept { \
    return nearest_kernel::screen<lane_type>(c, o, d, b, begin, out);                                            \
  }

}  // namespace raykernel::nearest_kernel
