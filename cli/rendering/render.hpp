// Rendering a scene of planes and meshes (scenes/scene.hpp) by ray casting (docs/ray-casting.md §1.1): for every
// pixel, for every sample, the exact nearest hit among the planes and the triangles (one query,
// raykernel/nearest_scene.hpp: a plane wins an exact tie) and simple legible shading. Rows are rendered in
// parallel.
//
// Robustness made visible: the stage image marks the pixels where the certified path needed a slower
// stage than the binary64 filter (for a relation, for ordering two t values, or for rounding the winner's t); the naive-difference image marks the pixels where the textbook loop in plain doubles
// (nearest_hit_naive, docs/ray-casting.md §1.1) picks another plane than the exact answer.
#pragma once

#include "rendering/png_image.hpp"
#include "scenes/scene.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <array>
#include <cstdint>
#include <functional>

namespace raykernel::cli {

// The slowest stage a traced nearest hit needed beyond the fast path, what `render --show-stages` marks:
// the slower of its relation and comparison stages, or its t stage if that is slower still. Rounding t
// starts at the compensated stage (the filter only gives signs), so a t rounded there is the fast path and
// counts as filter; expansion and exact count.
// (A TracedNearestHit of planes, or a TracedSceneHit of planes and triangles.)
template <class Traced>
[[nodiscard]] inline Stage slowest_stage(const Traced& traced) noexcept {
  Stage s = traced.relation_stage;
  if (traced.comparison_stage > s) s = traced.comparison_stage;
  if (traced.t_stage > Stage::compensated && traced.t_stage > s) s = traced.t_stage;
  return s;
}

struct RenderOptions {
  unsigned threads = 0;                  // 0: std::thread::hardware_concurrency()
  bool stage_image = false;              // fill RenderResult::stages
  bool compare_naive = false;            // run the naive pass: naive_difference and the naive counts
  bool naive_image = false;              // also fill RenderResult::naive (the scene as the naive loop sees it)
  bool legend = false;                   // label the stage and naive-difference images (legend.hpp)
  // Called from the calling thread about every 100 ms while rows are rendered, with the fraction done.
  std::function<void(double fraction)> progress;
};

struct RenderStats {
  std::uint64_t pixels = 0;
  std::uint64_t rays = 0;  // pixels × samples per pixel
  std::uint64_t hit_rays = 0;
  double seconds = 0;      // the certified pass alone (ray generation, nearest hit, shading)
  unsigned threads = 0;
  unsigned threads_ran = 0;  // of `threads`, those the system started (the calling thread included)
  // By raykernel::Stage: pixels (and rays) by the slowest stage any of their decisions needed, and the
  // comparisons of two t values each stage decided.
  std::array<std::uint64_t, stage_count> pixels_by_stage{};
  std::array<std::uint64_t, stage_count> rays_by_stage{};
  std::array<std::uint64_t, stage_count> comparisons_by_stage{};
  // The naive pass (compare_naive): pixels with at least one ray, and rays, where nearest_hit_naive picks
  // another plane (or hit/miss) than the certified nearest_hit.
  bool naive_compared = false;
  double naive_seconds = 0;
  std::uint64_t naive_pixels_differ = 0;
  std::uint64_t naive_rays_differ = 0;

  [[nodiscard]] double rays_per_second() const noexcept { return seconds > 0 ? static_cast<double>(rays) / seconds : 0; }
};

struct RenderResult {
  Image image;             // the render
  Image stages;            // with RenderOptions::stage_image
  Image naive_difference;  // with RenderOptions::compare_naive
  Image naive;             // with RenderOptions::naive_image
  RenderStats stats;
};

// The colours of the stage image (by raykernel::Stage; filter pixels stay grey) and of the pixels the
// naive loop gets wrong.
inline constexpr std::array<std::array<std::uint8_t, 3>, stage_count> stage_marker_colors = {{
    {0, 0, 0},        // filter: not marked
    {255, 205, 0},    // compensated: yellow
    {255, 110, 0},    // expansion: orange
    {220, 20, 90},    // exact: crimson
}};
inline constexpr std::array<std::uint8_t, 3> naive_difference_color = {255, 0, 255};  // magenta

// Renders `scene`. Throws invalid_input if a camera ray cannot be built (a degenerate camera that passed
// validation, which should not happen).
[[nodiscard]] RenderResult render_scene(const Scene& scene, const RenderOptions& options);

}  // namespace raykernel::cli
