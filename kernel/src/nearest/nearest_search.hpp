// The nearest-hit search: one ray against any number of surfaces of every kind (nearest/nearest_candidates.hpp
// has the candidates and how a kind plugs in). The feeders — planes() for a PlaneSet, mesh() for a PreparedMesh
// through its BVH — classify each surface once and offer its hits; the search keeps the best so far and one
// candidate being examined per kind (two slots each, so neither is ever copied), orders every hit against the
// best by the certified comparison of their exact t (compare_candidates), breaks exact ties by kind then index
// (wins_tie), and rounds t once, for the winner (kept in the candidate: the walk's pruning bound is certified
// from the filter's values, and only when it cannot be is a best's t rounded early, then reused). Used by
// nearest_hit for a plane set, a mesh and a scene of both (nearest/nearest_hit.cpp, mesh/nearest_mesh.cpp).
//
// A leaf's triangles are first screened four at a time (LeafScreen, nearest/triangle_candidate.hpp: the
// relation filter's first decision on four triangles in the lanes of one pass, the same bits as each triangle's
// own); a certain miss is recorded as classify would record it, a line certainly through a triangle's interior
// is decided from num alone (classify_screened), the others are classified one by one.
//
// Why the answer is the brute-force one:
//   - Every plane of the set that can win is examined (nearest/nearest_screen.hpp: the screen sets aside only
//     hits certainly farther than a plane the ray hits), and every triangle that can win is in a leaf the walk
//     returns: the bound passed to the walk is +inf until a hit is found, then a double b > t_best, so any
//     triangle with t ≤ t_best is kept (bvh.hpp's guarantee). The bound is a certified upper bound of
//     t_best (upper_bound_t, nextup(RN(t_best)) when it cannot do better), computed only when the best has
//     changed and the walk has boxes left to test.
//   - Each hit is compared with the best by the exact order of their t; an exact tie goes to the plane, then to
//     the smaller index, whatever order the candidates come in.
//   - A triangle with the previous candidate's vertices (repeats()) has its relation and t: it reuses them, and
//     the order of its t against the best is the previous one's (the best has not changed since, or is the
//     previous candidate).
#pragma once

#include "mesh/bvh_walk.hpp"
#include "nearest/exact_nearest.hpp"
#include "nearest/interval_bound.hpp"
#include "nearest/nearest_candidates.hpp"
#include "nearest/nearest_screen.hpp"
#include "nearest/plane_candidate.hpp"
#include "nearest/sphere_candidate.hpp"
#include "nearest/triangle_candidate.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/ray_plane_formula.hpp"

#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/nearest_scene.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <span>
#include <type_traits>

namespace raykernel::detail {

// The order of a plane's t and a triangle's in rationals (the exact stage across kinds).
[[nodiscard]] inline int exact_order(const Ray& ray, const HitCandidate& a, const TriangleCandidate& b) {
  return exact::compare_plane_triangle_t(ray, *a.plane, *b.source);
}
[[nodiscard]] inline int exact_order(const Ray& ray, const TriangleCandidate& a, const HitCandidate& b) {
  return -exact::compare_plane_triangle_t(ray, *b.plane, *a.source);
}
// A sphere's root against a plane's or a triangle's t, in rationals.
[[nodiscard]] inline int exact_order(const Ray& ray, const SphereCandidate& a, const HitCandidate& b) {
  return exact::compare_sphere_plane_t(ray, *a.sphere, a.root, *b.plane);
}
[[nodiscard]] inline int exact_order(const Ray& ray, const HitCandidate& a, const SphereCandidate& b) {
  return -exact::compare_sphere_plane_t(ray, *b.sphere, b.root, *a.plane);
}
[[nodiscard]] inline int exact_order(const Ray& ray, const SphereCandidate& a, const TriangleCandidate& b) {
  return exact::compare_sphere_triangle_t(ray, *a.sphere, a.root, *b.source);
}
[[nodiscard]] inline int exact_order(const Ray& ray, const TriangleCandidate& a, const SphereCandidate& b) {
  return -exact::compare_sphere_triangle_t(ray, *b.sphere, b.root, *a.source);
}

// The candidate planes of a set as columns (PlaneSet's friend).
struct PlaneSetColumns {
  static void build(PlaneSet& set) {
    const std::size_t count = set.candidates_.size();
    const std::size_t stride =
        (count + nearest_kernel::max_width - 1) / nearest_kernel::max_width * nearest_kernel::max_width;
    set.columns_.assign(6 * stride, 0);
    for (std::size_t j = 0; j < count; ++j) {
      const Plane& plane = set.planes_[set.candidates_[j]];
      const double values[6] = {plane.point.x,  plane.point.y,  plane.point.z,
                                plane.normal.x, plane.normal.y, plane.normal.z};
      for (std::size_t c = 0; c < 6; ++c) set.columns_[c * stride + j] = values[c];
    }
  }
  [[nodiscard]] static nearest_kernel::PlaneColumns of(const PlaneSet& set) noexcept {
    return {set.columns_.data(), set.columns_.size() / 6, set.candidates_.size()};
  }
};

// What a traced search counts, over every kind (TracedNearestHit, TracedMeshHit and TracedSceneHit are read off
// it).
struct SearchCounts {
  Stage relation_stage = Stage::filter;    // the slowest stage that decided a relation
  Stage comparison_stage = Stage::filter;  // the slowest stage that ordered two t
  std::array<std::uint64_t, stage_count> comparisons{};  // by the stage that decided them (ties without arithmetic: filter)
  // Triangles (TracedMeshHit):
  std::uint64_t candidates = 0, repeats = 0, hits = 0;
  std::array<std::uint64_t, stage_count> relations{};
  std::uint64_t near_ties = 0;                // comparisons the filter did not decide
  std::uint64_t ties_without_arithmetic = 0;  // of those, the exact ties seen from the vertices or at t = 0
  std::array<std::uint64_t, stage_count> tie_comparisons{};  // the others, by the stage that decided them
};

[[nodiscard]] constexpr Stage slower(Stage a, Stage b) noexcept { return a > b ? a : b; }

// What a traced search of planes or of a scene reports (TracedNearestHit, TracedSceneHit): the stages alone, in
// 40 bytes (a larger block of counters is cleared per ray with `rep stos`, whose start-up costs more than the
// counting).
struct StageCounts {
  Stage relation_stage = Stage::filter;
  Stage comparison_stage = Stage::filter;
  std::array<std::uint64_t, stage_count> comparisons{};
};

// NoTrace compiles to nothing.
struct NoTrace {
  void plane_relation(Stage) noexcept {}
  void triangle_candidate(Stage) noexcept {}
  void repeat() noexcept {}
  void triangle_hit() noexcept {}
  void comparison(const DistanceOrder&) noexcept {}
  void screened(std::uint32_t) noexcept {}
};
// Every count (SearchCounts), for the mesh's traced query.
struct Trace {
  SearchCounts* out;
  void plane_relation(Stage s) noexcept { out->relation_stage = slower(out->relation_stage, s); }
  void triangle_candidate(Stage s) noexcept {
    ++out->candidates;
    ++out->relations[static_cast<std::size_t>(s)];
    out->relation_stage = slower(out->relation_stage, s);
  }
  void repeat() noexcept {
    ++out->candidates;
    ++out->repeats;
  }
  void triangle_hit() noexcept { ++out->hits; }
  void comparison(const DistanceOrder& order) noexcept {
    ++out->comparisons[static_cast<std::size_t>(order.stage)];
    out->comparison_stage = slower(out->comparison_stage, order.stage);
    if (order.stage == Stage::filter && !order.without_arithmetic) return;
    ++out->near_ties;
    if (order.without_arithmetic) {
      ++out->ties_without_arithmetic;
    } else {
      ++out->tie_comparisons[static_cast<std::size_t>(order.stage)];
    }
  }
  void screened(std::uint32_t count) noexcept {  // hits the screen set aside: one filter comparison each
    out->comparisons[static_cast<std::size_t>(Stage::filter)] += count;
  }
};
// The stages only (StageCounts).
struct StageTrace {
  StageCounts* out;
  void plane_relation(Stage s) noexcept { out->relation_stage = slower(out->relation_stage, s); }
  void triangle_candidate(Stage s) noexcept { out->relation_stage = slower(out->relation_stage, s); }
  void repeat() noexcept {}
  void triangle_hit() noexcept {}
  void comparison(const DistanceOrder& order) noexcept {
    ++out->comparisons[static_cast<std::size_t>(order.stage)];
    out->comparison_stage = slower(out->comparison_stage, order.stage);
  }
  void screened(std::uint32_t count) noexcept { out->comparisons[static_cast<std::size_t>(Stage::filter)] += count; }
};

// Storage for one candidate, constructed in place when used (nothing is cleared per ray).
template <class T>
class Slot {
  static_assert(std::is_trivially_destructible_v<T>);

 public:
  Slot() noexcept {}  // NOLINT: left uninitialized
  template <class... Args>
  T& emplace(Args&&... args) noexcept {
    return *::new (static_cast<void*>(storage_)) T(static_cast<Args&&>(args)...);
  }
  [[nodiscard]] T& operator*() noexcept { return *std::launder(reinterpret_cast<T*>(storage_)); }

 private:
  alignas(T) unsigned char storage_[sizeof(T)];
};

template <class Tracer>
class NearestSearch {
 public:
  NearestSearch(const Ray& ray, Tracer tracer) noexcept : ray_(ray), tracer_(tracer) {}

  // Every plane of `set`: stage 1 of its relation in the scalar loop (screen null) or four or two planes at a time
  // by the screen, the rest of its cascade only when stage 1 cannot decide; each hit offered, in ascending index
  // order.
  // Every candidate plane of `set`, each hit whose exact t lies in `interval` offered (docs/contract.md §8: a valid
  // interval; within_interval decides each hit). The screen sets planes aside by comparison with one the ray hits,
  // which holds only for the whole ray: with another interval the caller passes none.
  [[gnu::always_inline]] void planes(const PlaneSet& set, nearest_kernel::ScreenFunction screen,
                                     const RayInterval& interval = {}) noexcept {
    const bool whole_ray = interval.t_min == 0 && interval.t_max == std::numeric_limits<double>::infinity();
    const double o[3] = {ray_.origin.x, ray_.origin.y, ray_.origin.z};
    const double d[3] = {ray_.direction.x, ray_.direction.y, ray_.direction.z};
    const std::span<const Plane> planes = set.planes();
    const std::span<const std::uint32_t> candidates = set.candidates();
    auto examine = [&](std::uint32_t k, const Dot3Rounded& den, const Dot3Rounded& num, std::int64_t den_filter,
                       std::int64_t num_filter) __attribute__((always_inline)) {
      const Plane& plane = planes[k];
      const int slot = best_ == Best::plane && plane_best_ == 0 ? 1 : 0;
      // A plane behind by the filter's signs is set aside before a candidate is made.
      if ((den_filter != uncertain_lane) & (num_filter != uncertain_lane) && signs_say_behind(num_filter, den_filter))
        return;
      HitCandidate& c = plane_[slot].emplace(k, ray_, plane, den, num);
      const Relation relation = c.decide_signs(den_filter, num_filter);
      tracer_.plane_relation(c.relation_stage);
      if (relation != Relation::hit) return;
      if (!whole_ray && !within_interval(ray_, c, interval)) return;
      offer(c, slot);
    };
    if (screen == nullptr) {
      for (const std::uint32_t k : candidates) {
        const Plane& plane = planes[k];
        const double n[3] = {plane.normal.x, plane.normal.y, plane.normal.z};
        const double diff[3] = {plane.point.x - o[0], plane.point.y - o[1], plane.point.z - o[2]};
        const Dot3Rounded den = dot3_rounded(d, n), num = dot3_rounded(diff, n);
        examine(k, den, num, dot3_filter_lanes(den, bounds::filter_den_relative),
                dot3_filter_lanes(num, bounds::filter_num_relative));
      }
    } else {
      const nearest_kernel::PlaneColumns columns = PlaneSetColumns::of(set);
      const nearest_kernel::Reference reference = screen->reference(columns, o, d);
      nearest_kernel::GroupStage1 group;
      for (std::size_t next = 0; next < columns.count;) {
        next = screen->screen(columns, o, d, reference, next, group);
        for (std::uint32_t lanes = group.examine; lanes != 0; lanes &= lanes - 1) {
          const unsigned lane = static_cast<unsigned>(__builtin_ctz(lanes));
          examine(candidates[group.first + lane], group.den(lane), group.num(lane), group.den_sign[lane],
                  group.num_sign[lane]);
        }
      }
      tracer_.screened(group.farther);
    }
  }

  // Every triangle of `mesh` the BVH walk returns, nearest leaf first, pruned by the best t so far; each
  // classified once under `rule` (or reused, repeats()) and each hit whose exact t lies in `interval` (a valid
  // one, docs/contract.md §8: the walk starts and ends at its bounds, within_interval decides each hit) offered.
  [[gnu::always_inline]] void mesh(const PreparedMesh& mesh, TriangleRule rule,
                                   const RayInterval& interval = {}) noexcept {
    const MeshBvh& bvh = mesh.bvh();
    if (bvh.nodes().empty()) return;
    constexpr double inf = std::numeric_limits<double>::infinity();
    triangle_[0].emplace();
    triangle_[1].emplace();
    BvhWalk walk;
    mesh_detail::start_walk(walk, bvh, ray_, interval.t_min, interval.t_max, mesh.leaf_triangles());
    const bool whole_ray = interval.t_min == 0 && interval.t_max == inf;
    const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
    const std::span<const Triangle> triangles = mesh.leaf_triangles();
    double bound = inf;
    bound_current_ = best_ == Best::none;
    TriangleCandidate* previous = nullptr;  // the last candidate classified (repeats reuse it)
    int previous_order = 0;                 // sign(t_previous − t_best), when the previous candidate is a hit
    bool previous_near_tie = false;         // and whether the filter could not order it against the best
    bool previous_in_interval = true;       // whether the previous candidate's t lies in the interval, for a hit
    BvhLeaf leaf;
    for (;;) {
      if (!bound_current_ && walk.stack_size > 0) {  // with no pending box, the walk ends whatever the bound
        bound = best_upper_bound();
        bound_current_ = true;
      }
      if (!next_leaf(walk, bound, leaf)) break;
      LeafScreen screen(ray_, triangles, leaf.position, leaf.triangles.size());
      for (std::size_t n = 0; n < leaf.triangles.size(); ++n) {
        const std::uint32_t position = static_cast<std::uint32_t>(leaf.position + n);
        const Triangle& tri = triangles[position];
        const std::uint32_t k = leaf.triangles[n];
        // A triangle the screen certainly misses is a miss whatever the previous one was (a repeat of a hit would
        // be a hit: the relation is a function of the exact input), so it is recorded without the repeat test.
        const bool missed = screen.certainly_missed(n);
        if (!missed && previous != nullptr && repeats(tri, *previous->source, previous->classification.location)) {
          tracer_.repeat();
          if (previous->classification.relation != TriangleRelation::hit || !previous_in_interval) continue;
          tracer_.triangle_hit();
          if (previous_order > 0) {  // its t is the previous one's: farther than the best
            if (previous_near_tie) tracer_.comparison(DistanceOrder{1, Stage::filter, true});  // as near, seen without arithmetic
            continue;
          }
          tracer_.comparison(DistanceOrder{0, Stage::filter, true});  // an exact tie with the best
          if (wins_tie(SurfaceKind::triangle, k, best_kind(), best_index())) {
            previous->take_identity(tri, k, position);
            triangle_best_ = previous == &*triangle_[0] ? 0 : 1;
            best_ = Best::triangle;  // the same t as before: the bound stands
          }
          continue;
        }
        const int slot = best_ == Best::triangle && triangle_best_ == 0 ? 1 : 0;
        TriangleCandidate& c = *triangle_[slot];
        if (missed) c.set_certain_miss(ray_, tri, k, position);
        else c.classify_screened(ray_, tri, k, position, rule, screen, n);
        tracer_.triangle_candidate(c.relation_stage);
        previous = &c;
        if (c.classification.relation != TriangleRelation::hit) continue;
        previous_in_interval = whole_ray || within_interval(ray_, c, interval);
        if (!previous_in_interval) continue;
        tracer_.triangle_hit();
        const DistanceOrder order = offer(c, slot);
        previous_order = order.sign;
        previous_near_tie = order.stage != Stage::filter || order.without_arithmetic;
      }
    }
  }

  // Every sphere of `set` with a root in `interval` (its smallest root there, docs/contract.md §8 and §10), each
  // classified and its roots rounded by the certified ray–sphere cascade (a miss the cascade's filter decides
  // costs that filter alone), offered as a candidate.
  // With the set's hierarchy (SphereSet::bvh), the leaves whose boxes the ray meets within the interval and not
  // beyond a double above the best exact t so far, nearest first: a sphere that could win or tie is in one of them
  // (bvh.hpp's guarantee), and the order of the offers does not change the winner (ties go by kind and index).
  void spheres(const SphereSet& set, const RayInterval& interval = {}) noexcept {
    const std::span<const Sphere> spheres = set.spheres();
    const auto candidate = [&](std::size_t k) {
      const int slot = best_ == Best::sphere && sphere_best_ == 0 ? 1 : 0;
      SphereCandidate& c = sphere_[slot].emplace();
      const bool hit = c.classify(ray_, spheres[k], k, interval);
      tracer_.plane_relation(c.relation_stage);  // the relation stage, whatever the kind
      if (hit) offer(c, slot);
    };
    if (const MeshBvh* bvh = set.bvh()) {
      BvhWalk walk;
      mesh_detail::start_walk(walk, *bvh, ray_, interval.t_min, interval.t_max);
      const auto next_leaf = mesh_detail::bvh_walk_functions().next_leaf;
      BvhLeaf leaf;
      while (next_leaf(walk, found() ? best_upper_bound() : std::numeric_limits<double>::infinity(), leaf))
        for (const std::uint32_t k : leaf.triangles) candidate(k);
      return;
    }
    for (std::size_t k = 0; k < spheres.size(); ++k) candidate(k);
  }

  [[nodiscard]] bool found() const noexcept { return best_ != Best::none; }
  [[nodiscard]] SurfaceKind winner_kind() const noexcept {
    return best_ == Best::plane ? SurfaceKind::plane : best_ == Best::triangle ? SurfaceKind::triangle : SurfaceKind::sphere;
  }
  [[nodiscard]] [[gnu::always_inline]] HitCandidate& plane_winner() noexcept { return *plane_[plane_best_]; }
  [[nodiscard]] [[gnu::always_inline]] TriangleCandidate& triangle_winner() noexcept { return *triangle_[triangle_best_]; }
  [[nodiscard]] [[gnu::always_inline]] SphereCandidate& sphere_winner() noexcept { return *sphere_[sphere_best_]; }

  // The winner's t, rounded once (or taken from the rounding the walk made for its bound), and the stage that
  // rounded it.
  [[gnu::always_inline]] double winner_t() noexcept { return best_t(); }
  [[nodiscard]] Stage winner_t_stage() noexcept {
    return best_ == Best::plane      ? plane_winner().t_stage
           : best_ == Best::triangle ? triangle_winner().t_stage
                                     : sphere_winner().t_stage;
  }

 private:
  enum class Best : std::uint8_t { none, plane, triangle, sphere };

  [[nodiscard]] SurfaceKind best_kind() const noexcept { return winner_kind(); }
  [[nodiscard]] [[gnu::always_inline]] std::size_t best_index() noexcept {
    return best_ == Best::plane      ? plane_winner().index
           : best_ == Best::triangle ? triangle_winner().index
                                     : sphere_winner().index;
  }
  [[gnu::always_inline]] double best_t() noexcept {
    return best_ == Best::plane      ? plane_winner().round_t()
           : best_ == Best::triangle ? triangle_winner().round_t()
                                     : sphere_winner().round_t();
  }
  // A double strictly above the sphere's exact t: nextup(RN(t)) (t ≤ RN(t) + ulp/2 < nextup(RN(t))).
  [[gnu::always_inline]] static double upper_bound_t(SphereCandidate& c) noexcept {
    return std::nextafter(c.t, std::numeric_limits<double>::infinity());
  }
  [[gnu::always_inline]] double best_upper_bound() noexcept {
    return best_ == Best::plane      ? upper_bound_t(plane_winner())
           : best_ == Best::triangle ? upper_bound_t(triangle_winner())
                                     : upper_bound_t(sphere_winner());
  }

  // A double strictly above the exact t of a hit, for the walk's pruning: b = (|N| + 2e)/(|D| − 2f) from the
  // stage-1 enclosures N ± e of num and D ± f of den (rounded as it comes: a guess, not a bound), certified above t
  // by compare_quotients_filter (proofs/compare/CompareQuotients.v, `compare_quotients_filter_sound`, on those enclosures
  // and the exact b/1: sign(t − b) = sign(num·1 − b·den)·sign(den)). When the filter cannot certify it (t = 0, a
  // den near zero, an overflow), nextup(RN(t)), with t rounded once and kept for the answer.
  template <class C>
  [[gnu::always_inline]] static double upper_bound_t(C& c) noexcept {
    if (c.num_sign != Sign::zero && !c.rounded) {
      const RoundedEnclosure n = c.num_filter(), d = c.den_filter();
      const double b = (std::fabs(n.value) + 2 * n.radius) / (std::fabs(d.value) - 2 * d.radius);
      const Sign delta = static_cast<Sign>(  // compare_quotients_filter, inlined
          compare_quotients_filter_lanes(n, d, RoundedEnclosure{b, 0}, RoundedEnclosure{1, 0}));
      if (is_certain(delta) && static_cast<int>(delta) * static_cast<int>(c.den_sign) < 0) return b;
    }
    return std::nextafter(c.round_t(), std::numeric_limits<double>::infinity());
  }

  // A hit in `slot` of its kind against the best: the order of t and t_best (0 for the first hit), and the best
  // updated when it is nearer, or tied and first by kind and index.
  template <class C>
  [[gnu::always_inline]] DistanceOrder offer(C& c, int slot) noexcept {
    if (best_ == Best::none) {
      make_best(c, slot);
      return DistanceOrder{0, Stage::filter};
    }
    const DistanceOrder order = best_ == Best::plane      ? compare_candidates(ray_, c, plane_winner())
                                : best_ == Best::triangle ? compare_candidates(ray_, c, triangle_winner())
                                                          : compare_candidates(ray_, c, sphere_winner());
    tracer_.comparison(order);
    if (order.sign < 0 || (order.sign == 0 && wins_tie(C::kind, c.index, best_kind(), best_index()))) make_best(c, slot);
    return order;
  }
  template <class C>
  [[gnu::always_inline]] void make_best(const C&, int slot) noexcept {
    if constexpr (C::kind == SurfaceKind::plane) {
      best_ = Best::plane;
      plane_best_ = slot;
    } else if constexpr (C::kind == SurfaceKind::triangle) {
      best_ = Best::triangle;
      triangle_best_ = slot;
    } else {
      best_ = Best::sphere;
      sphere_best_ = slot;
    }
    bound_current_ = false;
  }

  const Ray& ray_;
  Tracer tracer_;
  Best best_ = Best::none;
  int plane_best_ = 0, triangle_best_ = 0, sphere_best_ = 0;
  bool bound_current_ = true;
  Slot<HitCandidate> plane_[2];
  Slot<TriangleCandidate> triangle_[2];
  Slot<SphereCandidate> sphere_[2];
};

}  // namespace raykernel::detail
