// The batch API's fast loop: FastQueryT<Lanes8>::answer (certified/fast_path.hpp), the routine `intersect`
// runs, instantiated for eight queries at once with every operation per lane, over a range of a
// structure-of-arrays batch. It is compiled three times, once per instruction set, in fast_loop_avx512.cpp
// (-march=x86-64-v4: one zmm register per Lanes8), fast_loop_avx2.cpp (-march=x86-64-v3: two ymm, FMA) and
// fast_loop_portable.cpp (baseline x86-64 or any other target: SSE2, libm's correctly rounded fma per lane);
// batch.cpp picks one when first used. Separate translation units, not target_clones: GCC 12 fails with an
// internal error on 512-bit vector comparisons inside a target_clones function.
#pragma once

#include "certified/fast_path.hpp"
#include "certified/lanes.hpp"

#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>

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

[[gnu::always_inline]] inline detail::Lanes8 load8(const double* x) noexcept {
  detail::Lanes8 v;
  std::memcpy(&v, x, sizeof v);
  return v;
}

template <bool broadcast_plane>
[[gnu::always_inline]] inline void fast_loop(RayArrays r, PlaneArrays pl, std::size_t begin, std::size_t end,
                                             Relation* __restrict relation, double* __restrict t,
                                             std::uint8_t* __restrict outcome) noexcept {
  using detail::lane_count;
  using detail::Lanes8;
  std::size_t i = begin;
  for (; i + lane_count <= end; i += lane_count) {
    const Lanes8 o[3] = {load8(r.ox + i), load8(r.oy + i), load8(r.oz + i)};
    const Lanes8 d[3] = {load8(r.dx + i), load8(r.dy + i), load8(r.dz + i)};
    Lanes8 p[3], n[3];
    if constexpr (broadcast_plane) {
      p[0] = detail::broadcast(*pl.px), p[1] = detail::broadcast(*pl.py), p[2] = detail::broadcast(*pl.pz);
      n[0] = detail::broadcast(*pl.nx), n[1] = detail::broadcast(*pl.ny), n[2] = detail::broadcast(*pl.nz);
    } else {
      p[0] = load8(pl.px + i), p[1] = load8(pl.py + i), p[2] = load8(pl.pz + i);
      n[0] = load8(pl.nx + i), n[1] = load8(pl.ny + i), n[2] = load8(pl.nz + i);
    }
    const detail::FastAnswerT<Lanes8> a = detail::FastQueryT<Lanes8>(o, d, p, n).answer();
    std::memcpy(t + i, &a.t, sizeof a.t);
    const detail::Mask8 certified = a.relation_certain & a.t_certain;
    for (int lane = 0; lane < lane_count; ++lane) {
      relation[i + static_cast<std::size_t>(lane)] = a.behind[lane] ? Relation::behind : Relation::hit;
      outcome[i + static_cast<std::size_t>(lane)] = static_cast<std::uint8_t>(
          (certified[lane] & certified_by_fast_path) | (a.relation_by_compensated[lane] & relation_by_compensated));
    }
  }
  // The rest one at a time, with the same code for V = double.
  for (; i < end; ++i) {
    const std::size_t k = broadcast_plane ? 0 : i;
    const double o[3] = {r.ox[i], r.oy[i], r.oz[i]}, d[3] = {r.dx[i], r.dy[i], r.dz[i]};
    const double p[3] = {pl.px[k], pl.py[k], pl.pz[k]}, n[3] = {pl.nx[k], pl.ny[k], pl.nz[k]};
    const detail::FastAnswer a = detail::FastQuery(o, d, p, n).answer();
    t[i] = a.t;
    relation[i] = a.behind ? Relation::behind : Relation::hit;
    outcome[i] = static_cast<std::uint8_t>((a.relation_certain & a.t_certain ? unsigned{certified_by_fast_path} : 0u) |
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

#define RAYKERNEL_DEFINE_FAST_LOOPS(isa)                                                                      \
  namespace raykernel::batch_kernel::isa {                                                                   \
  void pairwise(RayArrays r, PlaneArrays p, std::size_t b, std::size_t e, Relation* rel, double* t,           \
                std::uint8_t* out) noexcept {                                                                 \
    fast_loop<false>(r, p, b, e, rel, t, out);                                                                \
  }                                                                                                           \
  void broadcast(RayArrays r, PlaneArrays p, std::size_t b, std::size_t e, Relation* rel, double* t,          \
                 std::uint8_t* out) noexcept {                                                                \
    fast_loop<true>(r, p, b, e, rel, t, out);                                                                 \
  }                                                                                                           \
  }

}  // namespace raykernel::batch_kernel
