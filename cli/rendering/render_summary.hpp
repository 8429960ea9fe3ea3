// What `raykernel render` prints: a header line before the render starts, then a line for each image written
// and the statistics. Each function returns whole lines ending in '\n'.
#pragma once

#include "rendering/render.hpp"
#include "scenes/scene.hpp"

#include <string>
#include <string_view>

namespace raykernel::cli {

// "raykernel render: demo scene, 960x540, 4 samples per pixel, 6 planes, 2 threads".
[[nodiscard]] std::string render_header(std::string_view scene_name, const Scene& scene, unsigned threads);

// After the render is written to `output`: the rays, time, rate and hits, and the pixels, rays and
// comparisons by stage.
[[nodiscard]] std::string render_statistics(std::string_view output, const RenderStats& stats);

// After the stage image is written to `path`.
[[nodiscard]] std::string stage_image_line(std::string_view path, const RenderStats& stats);

// The naive comparison (when it ran).
[[nodiscard]] std::string naive_comparison_line(const RenderStats& stats);

// After the naive-difference image and the naive image are written.
[[nodiscard]] std::string naive_difference_line(std::string_view path);
[[nodiscard]] std::string naive_image_line(std::string_view path);

// How the summary names an output: "standard output" for "-", else the path (printable bytes).
[[nodiscard]] std::string output_name(std::string_view path);

}  // namespace raykernel::cli
