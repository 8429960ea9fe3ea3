// Near ties between planes: one ray and two planes whose exact t along it are equal, or differ by less
// than one ulp of t, for testing nearest-hit code (docs/contract.md §4: the plane with the smallest exact t wins,
// ties go to the smaller index).
//
// A nearest-hit loop that compares t values rounded to doubles cannot order such planes: both t round to
// the same double (or to neighbours on either side of a rounding boundary), and code that computes t in
// plain floating point gets each one wrong by a few ulps, in either direction. The construction knows the
// exact order, so a test can check the winner without any arithmetic of its own:
//
//   const PlanePair pp = make_plane_pair_near_tie(bits);
//   EXPECT_EQ(my_nearest(pp.ray, pp.planes), pp.nearest());
//
// Every coordinate is an integer of at most 48 bits times a power of two, so the doubles hold the
// construction exactly and the promised relation between the two exact t is a theorem of the
// construction, not a floating-point estimate (plane_pairs.cpp; tests/plane_reference_check_test.cpp checks it
// in exact rationals). Both planes are hit (exact t > 0). The queries are always valid input.
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <array>
#include <cstdint>
#include <string_view>

namespace raykernel::testkit {

enum class PlaneTieKind : std::uint8_t {
  coincident,       // exact tie: the same geometric plane, given by another point and a normal scaled by ±2^k
  pivot,            // exact tie: two planes with different normals through a common point of the ray
  parallel_offset,  // near tie: two distinct parallel planes, closer along the ray than one ulp of t
  pivot_offset,     // near tie: two non-parallel planes whose hit points are less than one ulp of t apart
};
inline constexpr int plane_tie_kind_count = 4;
inline constexpr std::array<PlaneTieKind, plane_tie_kind_count> all_plane_tie_kinds = {
    PlaneTieKind::coincident, PlaneTieKind::pivot, PlaneTieKind::parallel_offset, PlaneTieKind::pivot_offset};

[[nodiscard]] std::string_view to_string(PlaneTieKind kind) noexcept;

// A ray and two planes it hits, with the exact order of their t.
//
// With t0, t1 the exact t of planes[0] and planes[1] (num/den as in docs/contract.md §1, both > 0):
//   * exact-tie kinds: t0 == t1 and order == 0;
//   * near-tie kinds: t0 != t1, |t1 − t0| < 2^-53·t0 (so less than one ulp of t0 and of t1: both
//     round to the same double or to adjacent ones), and order is the sign of t1 − t0.
struct PlanePair {
  PlaneTieKind kind;
  Ray ray;
  std::array<Plane, 2> planes;
  int order;  // sign of t1 − t0: −1, 0 or +1

  // The index docs/contract.md §4 answers for these two planes: the smaller exact t; on a tie, the smaller index.
  [[nodiscard]] int nearest() const noexcept { return order < 0 ? 1 : 0; }
  // The two one-plane queries, e.g. for the reference check.
  [[nodiscard]] Query query(int i) const noexcept { return {ray, planes[static_cast<std::size_t>(i)]}; }
};

// A pair of the given kind, or of a kind drawn from `bits`. Deterministic in the words drawn.
[[nodiscard]] PlanePair make_plane_pair_near_tie(PlaneTieKind kind, const BitSource& bits);
[[nodiscard]] PlanePair make_plane_pair_near_tie(const BitSource& bits);

}  // namespace raykernel::testkit
