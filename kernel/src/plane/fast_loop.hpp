// The batch API's fast loop: fast_answer (or fast_relation) of plane/ray_plane_stages.hpp, the routine
// `intersect` (or `relation`) runs, instantiated for eight queries at once with every operation per lane,
// over a range of a structure-of-arrays batch. It is compiled three times, once per instruction set, in fast_loop_avx512.cpp
// (-march=x86-64-v4: Lanes8, one zmm register), fast_loop_avx2.cpp (-march=x86-64-v3: Lanes4, one ymm, FMA)
// and fast_loop_portable.cpp (any target: one query at a time, libm's fma where there is no FMA unit);
// batch.cpp picks one when first used. Separate translation units, not target_clones: GCC 12 fails with an
// internal error on 512-bit vector comparisons inside a target_clones function.
#pragma once

#include "plane/ray_plane_stages.hpp"
#include "core/lanes.hpp"

#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace raykernel::batch_kernel {

// Per-query outcome of the fast loop.
enum : std::uint8_t { certified_by_fast_path = 1, relation_by_compensated = 2 };

// What the loop computes: the relation and t (intersect_batch), or the relation alone (relation_batch).
enum class LoopAnswer : bool { intersection, relation };

struct PlaneArrays {
  const double *px, *py, *pz, *nx, *ny, *nz;
};
struct RayArrays {
  const double *ox, *oy, *oz, *dx, *dy, *dz;
};

// Answers queries [begin, end): relation[i], t[i] (intersection loops only; t may be null for relation
// loops) and outcome[i] (the flags above). A query the fast path did not certify gets outcome 0 or
// relation_by_compensated, and must go through the full cascade.
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
template <class V, bool broadcast_plane, LoopAnswer what>
[[gnu::always_inline]] inline void fast_loop(RayArrays r, PlaneArrays pl, std::size_t begin, std::size_t end,
                                             Relation* __restrict relation, double* __restrict t,
                                             std::uint8_t* __restrict outcome) noexcept {
  constexpr std::size_t w = detail::width_of<V>;
  std::size_t i = begin;
  // The same code for a group of lanes (U = V) and for the tail, one query at a time (U = double).
  auto answer = []<class U>(const U o[3], const U d[3], const U p[3], const U n[3], U& t_out, detail::MaskOf<U>& behind,
                            detail::MaskOf<U>& certified, detail::MaskOf<U>& by_filter) {
    const detail::RayPlaneTermsT<U> q = detail::ray_plane_terms(o, d, p, n);
    if constexpr (what == LoopAnswer::intersection) {
      const detail::FastAnswerT<U> a = detail::fast_answer(q);
      t_out = a.t, behind = a.behind, certified = a.certain, by_filter = a.relation_by_filter;
    } else {
      const detail::FastRelationT<U> a = detail::fast_relation(q);
      behind = a.behind, certified = a.certain, by_filter = a.certain;
    }
  };
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
      V lane_t;
      detail::MaskOf<V> behind, certified, by_filter;
      answer(o, d, p, n, lane_t, behind, certified, by_filter);
      if constexpr (what == LoopAnswer::intersection) std::memcpy(t + i, &lane_t, sizeof lane_t);
      // Per lane: relation hit (0) or behind (1), and the outcome flags, narrowed to bytes in one conversion.
      using Bytes = std::conditional_t<w == 8, Bytes8, Bytes4>;
      const detail::MaskOf<V> flags = (certified & std::int64_t{certified_by_fast_path}) |
                                      (~by_filter & std::int64_t{relation_by_compensated});
      const Bytes relation_bytes = __builtin_convertvector(behind & static_cast<std::int64_t>(Relation::behind), Bytes);
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
    double lane_t = 0;
    bool behind = false, certified = false, by_filter = false;
    answer(o, d, p, n, lane_t, behind, certified, by_filter);
    if constexpr (what == LoopAnswer::intersection) t[i] = lane_t;
    relation[i] = behind ? Relation::behind : Relation::hit;
    outcome[i] = static_cast<std::uint8_t>((certified ? unsigned{certified_by_fast_path} : 0u) |
                                           (by_filter ? 0u : unsigned{relation_by_compensated}));
  }
}

// One instantiation per instruction set (fast_loop_<isa>.cpp defines RAYKERNEL_FAST_LOOP_NAMESPACE).
#define RAYKERNEL_DECLARE_FAST_LOOPS(isa)                                                                    \
  namespace isa {                                                                                           \
  void pairwise(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*, std::uint8_t*) noexcept; \
  void broadcast(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*, std::uint8_t*) noexcept; \
  void pairwise_relation(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*,                \
                         std::uint8_t*) noexcept;                                                             \
  void broadcast_relation(RayArrays, PlaneArrays, std::size_t, std::size_t, Relation*, double*,               \
                          std::uint8_t*) noexcept;                                                            \
  }
RAYKERNEL_DECLARE_FAST_LOOPS(portable)
RAYKERNEL_DECLARE_FAST_LOOPS(avx2)
RAYKERNEL_DECLARE_FAST_LOOPS(avx512)
#undef RAYKERNEL_DECLARE_FAST_LOOPS

// The loops are defined in the files compiled for each instruction set, which must check the floating-point
// requirements like every other translation unit with certified code.
#define RAYKERNEL_DEFINE_FAST_LOOP(isa, name, lane_type, broadcast_plane, what)                               \
  void raykernel::batch_kernel::isa::name(RayArrays r, PlaneArrays p, std::size_t b, std::size_t e,          \
                                          Relation* rel, double* t, std::uint8_t* out) noexcept {            \
    fast_loop<lane_type, broadcast_plane, what>(r, p, b, e, rel, t, out);                                     \
  }
#define RAYKERNEL_DEFINE_FAST_LOOPS(isa, lane_type)                                                           \
  RAYKERNEL_DEFINE_FAST_LOOP(isa, pairwise, lane_type, false, LoopAnswer::intersection)                       \
  RAYKERNEL_DEFINE_FAST_LOOP(isa, broadcast, lane_type, true, LoopAnswer::intersection)                       \
  RAYKERNEL_DEFINE_FAST_LOOP(isa, pairwise_relation, lane_type, false, LoopAnswer::relation)                  \
  RAYKERNEL_DEFINE_FAST_LOOP(isa, broadcast_relation, lane_type, true, LoopAnswer::relation)

}  // namespace raykernel::batch_kernel
