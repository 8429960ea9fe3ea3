#include "rendering/diagnostic_images.hpp"

#include "rendering/colour.hpp"
#include "rendering/legend.hpp"
#include "common/text_format.hpp"

#include <algorithm>

namespace raykernel::cli {

Image stage_image(const Image& render, const std::vector<std::uint8_t>& pixel_stage, const RenderStats& stats,
                  bool legend) {
  Image image(render.width, render.height);
  for (std::uint32_t row = 0; row < render.height; ++row)
    for (std::uint32_t i = 0; i < render.width; ++i) {
      std::uint8_t* px = image.pixel(i, row);
      const std::uint8_t s = pixel_stage[std::size_t{row} * render.width + i];
      if (s == static_cast<std::uint8_t>(Stage::filter)) store_grey(px, render.pixel(i, row));
      else std::copy(stage_marker_colors[s].begin(), stage_marker_colors[s].end(), px);
    }
  if (legend) {
    std::vector<LegendItem> items = {{std::nullopt, "past the filter:"}};
    for (std::size_t k = 1; k < stage_count; ++k)
      items.push_back({stage_marker_colors[k], std::string(to_string(static_cast<Stage>(k))) + " " +
                                                   with_thousands(stats.pixels_by_stage[k])});
    (void)draw_legend(image, items);
  }
  return image;
}

Image naive_difference_image(const Image& render, const std::vector<std::uint8_t>& differs, const RenderStats& stats,
                             bool legend) {
  Image image(render.width, render.height);
  for (std::uint32_t row = 0; row < render.height; ++row)
    for (std::uint32_t i = 0; i < render.width; ++i) {
      std::uint8_t* px = image.pixel(i, row);
      if (differs[std::size_t{row} * render.width + i])
        std::copy(naive_difference_color.begin(), naive_difference_color.end(), px);
      else
        store_grey(px, render.pixel(i, row));
    }
  if (legend) {
    (void)draw_legend(image, {{naive_difference_color, "plain doubles pick another surface: " +
                                                           count_of(stats.naive_pixels_differ, "pixel") + " (" +
                                                           percent(stats.naive_pixels_differ, stats.pixels) + ")"}});
  }
  return image;
}

}  // namespace raykernel::cli
