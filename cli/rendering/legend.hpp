// A legend strip for the diagnostic images of `raykernel render`: coloured swatches and short lowercase
// labels, drawn with a built-in 5 × 7 pixel font over the bottom rows of the image, so that a stage or
// naive-difference image explains itself when it is looked at alone.
#pragma once

#include "rendering/png_image.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::cli {

struct LegendItem {
  std::optional<std::array<std::uint8_t, 3>> swatch;  // a coloured square before the label
  std::string label;  // lowercase letters, digits, space and , . : ( ) % - /
};

// Draws the items left to right on a darkened strip along the bottom of `image`, at the largest scale
// (up to 2) at which they fit; draws nothing if they do not fit at scale 1. Returns whether it drew.
bool draw_legend(Image& image, const std::vector<LegendItem>& items);

}  // namespace raykernel::cli
