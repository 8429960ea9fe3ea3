// nearest_hit over a PlaneSet (docs/contract.md §4) and over a scene of planes, a mesh and spheres
// (raykernel/nearest_scene.hpp): the nearest-hit search (nearest/nearest_search.hpp) on those surfaces, then
// the winner's t rounded once. The mesh alone is mesh/nearest_mesh.cpp, on the same search.
//
// From screen_minimum candidate planes on, stage 1 of the planes' relations and a filter comparison with the t
// of one reference plane the ray hits run four (AVX2) or two planes at a time (nearest/nearest_screen.hpp), and
// only the planes that screen cannot set aside reach the search's scalar path.
#include <raykernel/nearest_hit.hpp>
#include <raykernel/nearest_scene.hpp>

#include "core/fp_environment.hpp"
#include "core/fp_requirements.hpp"
#include "core/multiversion.hpp"
#include "core/validation.hpp"
#include "nearest/nearest_hit_internal.hpp"
#include "nearest/nearest_search.hpp"
#include "nearest/nearest_screen.hpp"
#include "plane/exact_plane.hpp"
#include "plane/exact_plane_compare.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace raykernel {
namespace detail {
namespace {

void throw_if_invalid(const Ray& ray) {
  if (!is_valid(ray)) [[unlikely]]
    throw invalid_input(*validate(ray));
}

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

// ---- a plane set ---------------------------------------------------------------------------------------------

// For a valid ray, in the default environment, with a screen or (null) the scalar loop.
template <class Tracer>
[[gnu::always_inline]] inline std::optional<NearestHit> nearest_plane(const Ray& ray, const PlaneSet& set,
                                                                      nearest_kernel::ScreenFunction screen,
                                                                      Tracer tracer, Stage& t_stage) noexcept {
  NearestSearch<Tracer> search(ray, tracer);
  search.planes(set, screen);
  if (!search.found()) return std::nullopt;
  HitCandidate& winner = search.plane_winner();
  const double t = winner.round_t();
  t_stage = winner.t_stage;
  return NearestHit{winner.index, t};
}


// Within an interval other than the whole ray: the scalar loop, each hit ordered against the bounds.
RAYKERNEL_MULTIVERSION
std::optional<NearestHit> nearest_within(const Ray& ray, const RayInterval& interval, const PlaneSet& set) noexcept {
  NearestSearch<NoTrace> search(ray, NoTrace{});
  search.planes(set, nullptr, interval);
  if (!search.found()) return std::nullopt;
  HitCandidate& winner = search.plane_winner();
  return NearestHit{winner.index, winner.round_t()};
}

RAYKERNEL_MULTIVERSION
std::optional<NearestHit> nearest_untraced(const Ray& ray, const PlaneSet& set) noexcept {
  Stage t_stage;
  return nearest_plane(ray, set, screen_for(set), NoTrace{}, t_stage);
}

RAYKERNEL_MULTIVERSION
TracedNearestHit nearest_traced(const Ray& ray, const PlaneSet& set, nearest_kernel::ScreenFunction screen) noexcept {
  StageCounts counts;
  Stage t_stage = Stage::filter;
  const std::optional<NearestHit> hit = nearest_plane(ray, set, screen, StageTrace{&counts}, t_stage);
  TracedNearestHit trace{hit, counts.relation_stage, counts.comparison_stage, hit ? t_stage : Stage::filter, {}};
  for (std::size_t s = 0; s < stage_count; ++s) trace.comparisons[s] = static_cast<std::uint32_t>(counts.comparisons[s]);
  return trace;
}

// ---- a scene -------------------------------------------------------------------------------------------------

template <class Tracer>
[[gnu::always_inline]] inline std::optional<SurfaceHit> nearest_in_scene(const Ray& ray, const NearestScene& scene,
                                                                         const NearestOptions& options, Tracer tracer,
                                                                         Stage& t_stage) noexcept {
  NearestSearch<Tracer> search(ray, tracer);
  if (scene.planes != nullptr) search.planes(*scene.planes, screen_for(*scene.planes));
  if (scene.spheres != nullptr) search.spheres(*scene.spheres);  // before the mesh: its walk prunes by the best
  if (scene.mesh != nullptr) search.mesh(*scene.mesh, scene.rule);
  if (!search.found()) return std::nullopt;
  const double t = search.winner_t();
  t_stage = search.winner_t_stage();
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (search.winner_kind() == SurfaceKind::plane)
    return SurfaceHit{SurfaceKind::plane, search.plane_winner().index, t, {nan, nan, nan}};
  if (search.winner_kind() == SurfaceKind::sphere)
    return SurfaceHit{SurfaceKind::sphere, search.sphere_winner().index, t, {nan, nan, nan}};
  const TriangleCandidate& winner = search.triangle_winner();
  SurfaceHit hit{SurfaceKind::triangle, winner.index, t, {nan, nan, nan}};
  if (options.barycentric) hit.barycentric = triangle_barycentric(ray, *winner.triangle, scene.rule);
  return hit;
}

RAYKERNEL_MULTIVERSION
std::optional<SurfaceHit> scene_untraced(const Ray& ray, const NearestScene& scene, const NearestOptions& options) noexcept {
  Stage t_stage;
  return nearest_in_scene(ray, scene, options, NoTrace{}, t_stage);
}

RAYKERNEL_MULTIVERSION
TracedSceneHit scene_traced(const Ray& ray, const NearestScene& scene, const NearestOptions& options) noexcept {
  StageCounts counts;
  Stage t_stage = Stage::filter;
  const std::optional<SurfaceHit> hit = nearest_in_scene(ray, scene, options, StageTrace{&counts}, t_stage);
  return TracedSceneHit{hit, counts.relation_stage, counts.comparison_stage, hit ? t_stage : Stage::filter,
                        counts.comparisons};
}

}  // namespace

RAYKERNEL_MULTIVERSION
DistanceOrder compare_hit_distances(HitCandidate& a, HitCandidate& b) noexcept {
  return compare_candidates(*a.ray, a, b);
}

TracedNearestHit nearest_traced_with_screen(const Ray& ray, const PlaneSet& set, nearest_kernel::ScreenFunction screen) {
  throw_if_invalid(ray);
  return in_default_fp_environment([&] { return nearest_traced(ray, set, screen); });
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
  return detail::in_default_fp_environment(
      [&] { return detail::nearest_traced(ray, planes, detail::screen_for(planes)); });
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

std::string_view to_string(SurfaceKind kind) noexcept {
  switch (kind) {
    case SurfaceKind::plane: return "plane";
    case SurfaceKind::triangle: return "triangle";
    case SurfaceKind::sphere: return "sphere";
  }
  return "?";
}

std::optional<NearestHit> nearest_hit(const Ray& ray, const RayInterval& interval, const PlaneSet& planes) {
  detail::throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&] {
    if (interval.t_min == 0 && std::isinf(interval.t_max))  // the whole ray (a valid t_max is +inf or finite)
      return detail::nearest_untraced(ray, planes);
    return detail::nearest_within(ray, interval, planes);
  });
}

std::optional<SphereHit> nearest_hit(const Ray& ray, const RayInterval& interval, const SphereSet& spheres) {
  detail::throw_if_invalid(ray);
  detail::throw_if_invalid_interval(interval);
  return detail::in_default_fp_environment([&]() -> std::optional<SphereHit> {
    detail::NearestSearch<detail::NoTrace> search(ray, detail::NoTrace{});
    search.spheres(spheres, interval);
    if (!search.found()) return std::nullopt;
    return SphereHit{search.sphere_winner().index, search.winner_t()};
  });
}

std::optional<SurfaceHit> nearest_hit(const Ray& ray, const NearestScene& scene, const NearestOptions& options) {
  detail::throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return detail::scene_untraced(ray, scene, options); });
}

TracedSceneHit nearest_hit_traced(const Ray& ray, const NearestScene& scene, const NearestOptions& options) {
  detail::throw_if_invalid(ray);
  return detail::in_default_fp_environment([&] { return detail::scene_traced(ray, scene, options); });
}

}  // namespace raykernel
