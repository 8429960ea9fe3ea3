// nearest_hit: the plane with the smallest exact t among those a ray hits (docs/contract.md §4), over a
// PlaneSet prepared once (validated, coincident planes set aside).
//
// Per plane, stage 1 of the relation (the binary64 filter of den and num) in the common case, the rest of
// the cascade only for planes it cannot decide. Per hit, the certified comparison with the best so far
// (nearest/compare_quotients.hpp), starting from the same stage-1 values and escalating stage by stage
// only when a comparison needs it. t is rounded once, for the winner. From screen_minimum candidate planes
// on, stage 1 and a filter comparison with the t of one reference plane the ray hits run four (AVX2) or two
// planes at a time (nearest/nearest_screen.hpp), and only the planes that screen cannot set aside reach the
// scalar path.
#include <raykernel/nearest_hit.hpp>

#include "nearest/compare_quotients.hpp"
#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "plane/ray_plane_cascade.hpp"
#include "plane/exact_plane.hpp"
#include "plane/exact_plane_compare.hpp"
#include "core/fp_environment.hpp"
#include "nearest/nearest_hit_internal.hpp"
#include "nearest/nearest_screen.hpp"
#include "plane/ray_plane_formula.hpp"
#include "core/validation.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace raykernel {
namespace detail {
namespace {

[[nodiscard]] Stage slower(Stage a, Stage b) noexcept { return a > b ? a : b; }

void throw_if_invalid(const Ray& ray) {
  if (!is_valid(ray)) throw invalid_input(*validate(ray));
}

// Records the stages of a traced query; NoTrace compiles to nothing.
struct NoTrace {
  void relation(Stage) noexcept {}
  void comparison(Stage) noexcept {}
  void comparisons(Stage, std::uint32_t) noexcept {}
};
struct Trace {
  TracedNearestHit* out;
  void relation(Stage s) noexcept { out->relation_stage = slower(out->relation_stage, s); }
  void comparison(Stage s) noexcept {
    ++out->comparisons[static_cast<std::size_t>(s)];
    out->comparison_stage = slower(out->comparison_stage, s);
  }
  void comparisons(Stage s, std::uint32_t count) noexcept {
    out->comparisons[static_cast<std::size_t>(s)] += count;
    if (count != 0) out->comparison_stage = slower(out->comparison_stage, s);
  }
};

}  // namespace

RAYKERNEL_MULTIVERSION
DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b) noexcept {
  // t = 0 exactly (the origin on the plane) comes first; num's sign is exact.
  const bool a_at_origin = a.num_sign == Sign::zero, b_at_origin = b.num_sign == Sign::zero;
  if (a_at_origin || b_at_origin) return {static_cast<int>(!a_at_origin) - static_cast<int>(!b_at_origin), Stage::filter};

  // sign(t_a − t_b) = sign(Δ)·sign(den_a)·sign(den_b).
  const int orientation = a.den_sign == b.den_sign ? 1 : -1;
  Sign delta = compare_quotients_filter(filter_enclosure(a.num, bounds::filter_num_relative),
                                        filter_enclosure(a.den, bounds::filter_den_relative),
                                        filter_enclosure(b.num, bounds::filter_num_relative),
                                        filter_enclosure(b.den, bounds::filter_den_relative));
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::filter};

  RayPlaneCascade& qa = a.cascade();
  RayPlaneCascade& qb = b.cascade();
  delta = enclosure_sign(compare_quotients_compensated(qa.num_compensated(), qa.den_compensated(),
                                                       qb.num_compensated(), qb.den_compensated()));
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::compensated};

  delta = compare_quotients_expansion(qa.expansions(), qb.expansions());
  if (is_certain(delta)) return {orientation * static_cast<int>(delta), Stage::expansion};

  return {orientation * exact::compare_quotients(*a.ray, *a.plane, *b.plane), Stage::exact};
}

namespace {

// The instruction set of the screen (nearest/nearest_screen.hpp), chosen once: AVX2, or portable.
constexpr nearest_kernel::ScreenFunctions portable_screen{nearest_kernel::portable::reference,
                                                          nearest_kernel::portable::screen};
#if defined(RAYKERNEL_NEAREST_AVX2)
constexpr nearest_kernel::ScreenFunctions avx2_screen{nearest_kernel::avx2::reference, nearest_kernel::avx2::screen};
#endif
nearest_kernel::ScreenFunction screen_function() noexcept {
  static const nearest_kernel::ScreenFunction screen = [] {
#if defined(RAYKERNEL_NEAREST_AVX2)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("x86-64-v3")) return &avx2_screen;
#endif
    return &portable_screen;
  }();
  return screen;
}

// Below this many candidate planes the scalar loop is used: its fixed cost is lower (the screen makes two
// passes, and recomputes the reference plane's stage 1). Measured (bench/README.md, "nearest"): at 4 planes
// the screen is slower (demo4 by about 1.4×), from 8 on faster; 5 to 7 were within the noise of a shared
// machine.
constexpr std::size_t screen_minimum = 8;

[[nodiscard]] nearest_kernel::ScreenFunction screen_for(const PlaneSet& set) noexcept {
  return set.candidates().size() < screen_minimum ? nullptr : screen_function();
}

}  // namespace

// The candidate planes of a set as columns (PlaneSet's friend).
struct PlaneSetColumns {
  static void build(PlaneSet& set) {
    const std::size_t count = set.candidates_.size();
    const std::size_t stride = (count + nearest_kernel::max_width - 1) / nearest_kernel::max_width * nearest_kernel::max_width;
    set.columns_.assign(6 * stride, 0.0);
    for (std::size_t j = 0; j < count; ++j) {
      const Plane& plane = set.planes_[set.candidates_[j]];
      const double values[6] = {plane.point.x, plane.point.y, plane.point.z, plane.normal.x, plane.normal.y, plane.normal.z};
      for (std::size_t c = 0; c < 6; ++c) set.columns_[c * stride + j] = values[c];
    }
  }
  [[nodiscard]] static nearest_kernel::PlaneColumns of(const PlaneSet& set) noexcept {
    const std::size_t count = set.candidates_.size();
    return {set.columns_.data(), set.columns_.size() / 6, count};
  }
};

namespace {

// For a valid ray, in the default environment, with a screen or (null) the scalar loop. The multiversioned functions here are noexcept (see
// plane/ray_plane_stages.hpp): the ray is validated before.
//
// Each candidate plane's stage-1 values come from the screen (four or two planes at a time), or from the
// scalar loop below; `examine` is the rest for one plane, in ascending candidate order.
template <class Tracer>
[[gnu::always_inline]] inline std::optional<NearestHit> nearest_in_default_environment(
    const Ray& ray, const PlaneSet& set, nearest_kernel::ScreenFunction screen, Tracer tracer, Stage& t_stage) noexcept {
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const std::span<const Plane> planes = set.planes();
  const std::span<const std::uint32_t> candidates = set.candidates();
  // Two slots: the best candidate so far and the one being examined, so neither is ever copied.
  std::optional<HitCandidate> slot[2];
  int best = -1;
  // One plane given its stage-1 values and signs, in ascending candidate order.
  auto examine = [&](std::uint32_t k, const Dot3Rounded& den, const Dot3Rounded& num, std::int64_t den_filter,
                     std::int64_t num_filter) {
    const Plane& plane = planes[k];
    const int current = best == 0 ? 1 : 0;
    if ((den_filter != uncertain_lane) & (num_filter != uncertain_lane)) [[likely]] {
      if (signs_say_behind(num_filter, den_filter)) return;
      HitCandidate& c = slot[current].emplace(k, ray, plane, den, num);
      c.num_sign = static_cast<Sign>(num_filter);
      c.den_sign = static_cast<Sign>(den_filter);
      tracer.relation(Stage::filter);
    } else {
      HitCandidate& c = slot[current].emplace(k, ray, plane, den, num);
      const CertifiedSigns signs = certified_signs(c.cascade());
      tracer.relation(signs.stage);
      if (relation_from_signs(static_cast<int>(signs.num), static_cast<int>(signs.den)) != Relation::hit) return;
      c.num_sign = signs.num;
      c.den_sign = signs.den;
      c.relation_stage = signs.stage;
    }
    if (best < 0) {
      best = current;
      return;
    }
    const DistanceOrder order = compare_hit_distances(*slot[current], *slot[best]);
    tracer.comparison(order.stage);
    if (order.sign < 0) best = current;  // strictly nearer; a tie keeps the smaller index
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
    tracer.comparisons(Stage::filter, group.farther);
  }
  if (best < 0) return std::nullopt;

  HitCandidate& winner = *slot[best];
  if (winner.num_sign == Sign::zero) {  // exact zero: +0, decided with the relation
    t_stage = winner.relation_stage;
    return NearestHit{winner.index, 0.0};
  }
  RayPlaneCascade& cascade = winner.cascade();
  if (winner.relation_stage == Stage::exact) {  // extreme exponents: the exact stage rounds t too
    t_stage = Stage::exact;
    return NearestHit{winner.index, exact::intersect(ray, *winner.plane).t};
  }
  const auto [t, stage] = certified_quotient(cascade);
  t_stage = stage;
  return NearestHit{winner.index, t};
}

RAYKERNEL_MULTIVERSION
std::optional<NearestHit> nearest_untraced(const Ray& ray, const PlaneSet& set) noexcept {
  Stage t_stage;
  return nearest_in_default_environment(ray, set, screen_for(set), NoTrace{}, t_stage);
}

RAYKERNEL_MULTIVERSION
TracedNearestHit nearest_traced(const Ray& ray, const PlaneSet& set) noexcept {
  TracedNearestHit trace;
  trace.hit = nearest_in_default_environment(ray, set, screen_for(set), Trace{&trace}, trace.t_stage);
  if (!trace.hit) trace.t_stage = Stage::filter;
  return trace;
}

}  // namespace

TracedNearestHit nearest_traced_with_screen(const Ray& ray, const PlaneSet& set, nearest_kernel::ScreenFunction screen) {
  throw_if_invalid(ray);
  return in_default_fp_environment([&] {
    TracedNearestHit trace;
    trace.hit = nearest_in_default_environment(ray, set, screen, Trace{&trace}, trace.t_stage);
    if (!trace.hit) trace.t_stage = Stage::filter;
    return trace;
  });
}

nearest_kernel::ScreenFunction chosen_screen() noexcept { return screen_function(); }
}  // namespace detail

PlaneSet::PlaneSet(std::span<const Plane> planes) : planes_(planes.begin(), planes.end()) {
  for (std::size_t k = 0; k < planes_.size(); ++k)
    if (!detail::is_valid(planes_[k]))
      throw invalid_input("plane " + std::to_string(k) + ": " + *validate(planes_[k]));
  detail::in_default_fp_environment([&] { candidates_ = detail::exact::distinct_planes(planes_); });
  detail::PlaneSetColumns::build(*this);
}

std::optional<NearestHit> nearest_hit(const Ray& ray, const PlaneSet& planes) {
  detail::throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return detail::nearest_untraced(ray, planes); });
}

// The ray is checked before the planes, as the contract's CLI reports a bad ray line before anything else.
std::optional<NearestHit> nearest_hit(const Ray& ray, std::span<const Plane> planes) {
  detail::throw_if_invalid(ray);
  return nearest_hit(ray, PlaneSet(planes));
}

TracedNearestHit nearest_hit_traced(const Ray& ray, const PlaneSet& planes) {
  detail::throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return detail::nearest_traced(ray, planes); });
}

TracedNearestHit nearest_hit_traced(const Ray& ray, std::span<const Plane> planes) {
  detail::throw_if_invalid(ray);
  return nearest_hit_traced(ray, PlaneSet(planes));
}

std::optional<NearestHit> nearest_hit_exact(const Ray& ray, std::span<const Plane> planes) {
  return detail::in_default_fp_environment([&]() -> std::optional<NearestHit> {
    if (auto reason = validate(ray)) throw invalid_input(*reason);
    for (std::size_t k = 0; k < planes.size(); ++k)
      if (auto reason = validate(planes[k])) throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
    const std::optional<std::size_t> k = detail::exact::nearest_plane(ray, planes);
    if (!k) return std::nullopt;
    return NearestHit{*k, detail::exact::intersect(ray, planes[*k]).t};
  });
}

std::optional<NearestHit> nearest_hit_naive(const Ray& ray, std::span<const Plane> planes) noexcept {
  std::optional<NearestHit> best;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const Intersection r = intersect_naive(ray, planes[k]);
    if (r.relation != Relation::hit) continue;
    if (!best || r.t < best->t) best = NearestHit{k, r.t};
  }
  return best;
}

}  // namespace raykernel
