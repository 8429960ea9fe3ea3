// The diagnostic images of `raykernel render` and their legends: the stage image (pixels where the certified
// path needed a slower stage than the binary64 filter, coloured by stage) and the naive-difference image
// (pixels where the naive loop picks another plane, in magenta), both over a dimmed grey copy of the render.
#pragma once

#include "rendering/png_image.hpp"
#include "rendering/render.hpp"

#include <cstdint>
#include <vector>

namespace raykernel::cli {

// `pixel_stage` holds, row-major like the image, each pixel's slowest raykernel::Stage. With `legend`, the
// counts of stats.pixels_by_stage are written over the bottom rows.
[[nodiscard]] Image stage_image(const Image& render, const std::vector<std::uint8_t>& pixel_stage,
                                const RenderStats& stats, bool legend);

// `differs` holds, row-major, 1 for the pixels where some ray's naive answer differs. With `legend`, the
// count and share of stats.naive_pixels_differ.
[[nodiscard]] Image naive_difference_image(const Image& render, const std::vector<std::uint8_t>& differs,
                                           const RenderStats& stats, bool legend);

}  // namespace raykernel::cli
