// The batch API's fast loop: FastQueryT<Lanes8>::answer (certified/fast_path.hpp), the routine `intersect`
// runs, instantiated for eight queries at once with every operation per lane, over a range of a
// structure-of-arrays batch. It is compiled three times, once per instruction set, in fast_loop_avx512.cpp
// (-march=x86-64-v4: Lanes8, one zmm register), fast_loop_avx2.cpp (-march=x86-64-v3: Lanes4, one ymm, FMA)
// and fast_loop_portable.cpp (any target: one query at a time, libm's fma where there is no FMA unit);
// batch.cpp picks one when first used. Separate translation units, not target_clones: GCC 12 fails with an
// internal error on 512-bit vector comparisons inside a target_clones function.
#pragma once

#include "certified/fast_path.hpp"
#include "certified/lanes.hpp"

#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace raykernel::batch_kernel {

// Per-query outcome of the fast loop.
enum : std::uint8_t { certified_by_fast_path = 1, relation_by_compensated = 2 };

struct PlaneArrays {
  const double *px, *py, *pz, *nx, *ny, *nz;
};
struct RayArrays {
  const double *ox, *oy, *oz, *dx, *dy, *dz;
};

// Answers queries [begin, end): relation[i], t[i] and outcome[i] (the flags above). A query the fast path
// did not certify gets outcome 0 or relation_by_compensated, and must go through the full cascade.
using LoopFunction = void (*)(RayArrays rays, PlaneArrays planes, std::size_t begin, std::size_t end,
                              Relation* relation, double* t, std::uint8_t* outcome);

using Bytes4 = std::uint8_t __attribute__((vector_size(4)));
using Bytes8 = std::uint8_t __attribute__((vector_size(8)));

template <class V>
[[gnu::always_inline]] inline V load(const double* x) noexcept {
  V v;
  std::memcpy(&v, x, sizeof v);
  return v;
}

// V: the lane type (Lanes8 for AVX-512, Lanes4 for AVX2; double runs one query at a time).
template <class V, bool broadcast_plane>
[[gnu::always_inline]] inline void fast_loop(RayArrays r, PlaneArrays pl, std::size_t begin, std::size_t end,
                                             Relation* __restrict relation, double* __restrict t,
                                             std::uint8_t* __restrict outcome) noexcept {
  constexpr std::size_t w = detail::width_of<V>;
  std::size_t i = begin;
  if constexpr (w > 1) {
    for (; i + w <= end; i += w) {
      const V o[3] = {load<V>(r.ox + i), load<V>(r.oy + i), load<V>(r.oz + i)};
      const V d[3] = {load<V>(r.dx + i), load<V>(r.dy + i), load<V>(r.dz + i)};
      V p[3], n[3];
      if constexpr (broadcast_plane) {
        p[0] = detail::broadcast<V>(*pl.px), p[1] = detail::broadcast<V>(*pl.py), p[2] = detail::broadcast<V>(*pl.pz);
        n[0] = detail::broadcast<V>(*pl.nx), n[1] = detail::broadcast<V>(*pl.ny), n[2] = detail::broadcast<V>(*pl.nz);
      } else {
        p[0] = load<V>(pl.px + i), p[1] = load<V>(pl.py + i), p[2] = load<V>(pl.pz + i);
        n[0] = load<V>(pl.nx + i), n[1] = load<V>(pl.ny + i), n[2] = load<V>(pl.nz + i);
      }
      const detail::FastAnswerT<V> a = detail::FastQueryT<V>(o, d, p, n).answer();
      std::memcpy(t + i, &a.t, sizeof a.t);
      // Per lane: relation hit (0) or behind (1), and the outcome flags, narrowed to bytes in one conversion.
      using Bytes = std::conditional_t<w == 8, Bytes8, Bytes4>;
      const detail::MaskOf<V> flags = ((a.relation_certain & a.t_certain) & std::int64_t{certified_by_fast_path}) |
                                      (a.relation_by_compensated & std::int64_t{relation_by_compensated});
      const Bytes relation_bytes =
          __builtin_convertvector(a.behind & static_cast<std::int64_t>(Relation::behind), Bytes);
      const Bytes outcome_bytes = __builtin_convertvector(flags, Bytes);
      static_assert(sizeof(Relation) == 1 && static_cast<int>(Relation::hit) == 0);
      std::memcpy(relation + i, &relation_bytes, w);
      std::memcpy(outcome + i, &outcome_bytes, w);
    }
  }
  // The rest (or everything, for V = double) one at a time, with the same code for double.
  for (; i < end; ++i) {
    const std::size_t k = broadcast_plane ? 0 : i;
    const double o[3] = {r.ox[i], r.oy[i], r.oz[i]}, d[3] = {r.dx[i], r.dy[i], r.dz[i]};
    const double p[3] = {pl.px[k], pl.py[k], pl.pz[k]}, n[3] = {pl.nx[k], pl.ny[k], pl.nz[k]};
    const detail::FastAnswer a = detail::FastQuery(o, d, p, n).answer();
    t[i] = a.t;
    relation[i] = a.behind ? Relation::behind : Relation::hit;
    const bool certified = a.relation_certain & a.t_certain;
    outcome[i] = static_cast<std::uint8_t>((certified ? unsigned{certified_by_fast_path} : 0u) |
                                           (a.relation_by_compensated ? unsigned{relation_by_compensated} : 0u));
  }
}

// One instantiation per instruction set (fast_loop_<isa>.cpp defines RAYKERNEL_FAST_LOOP_NAMESPACE).
#define RAYKERNEL_DECLARE_FAST_LOOPS(isa)                                                                    \
  namespace isa {                                                                                           \
  void pairwise(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*, std::uint8_t*) noexcept; \
  void broadcast(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*, std::uint8_t*) noexcept; \
  }
RAYKERNEL_DECLARE_FAST_LOOPS(portable)
RAYKERNEL_DECLARE_FAST_LOOPS(avx2)
RAYKERNEL_DECLARE_FAST_LOOPS(avx512)
#undef RAYKERNEL_DECLARE_FAST_LOOPS

#define RAYKERNEL_DEFINE_FAST_LOOPS(isa, lane_type)                                                           \
  namespace raykernel::batch_kernel::isa {                                                                   \
  void pairwise(RayArrays r, PlaneArrays p, std::size_t b, std::size_t e, Relation* rel, double* t,           \
                std::uint8_t* out) noexcept {                                                                 \
    fast_loop<lane_type, false>(r, p, b, e, rel, t, out);                                                     \
  }                                                                                                           \
  void broadcast(RayArrays r, PlaneArrays p, std::size_t b, std::size_t e, Relation* rel, double* t,          \
                 std::uint8_t* out) noexcept {                                                                \
    fast_loop<lane_type, true>(r, p, b, e, rel, t, out);                                                      \
  }                                                                                                           \
  }

}  // namespace raykernel::batch_kernel
