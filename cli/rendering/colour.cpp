#include "rendering/colour.hpp"

#include <algorithm>
#include <cmath>

namespace raykernel::cli {
namespace {

double srgb_to_linear(double c) noexcept { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double linear_to_srgb(double c) noexcept {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}
std::uint8_t to_byte(double display) noexcept {
  return static_cast<std::uint8_t>(std::lround(std::clamp(display, 0.0, 1.0) * 255));
}

}  // namespace

Linear linear(const Rgb& c) noexcept { return {srgb_to_linear(c.r), srgb_to_linear(c.g), srgb_to_linear(c.b)}; }

void store(std::uint8_t* px, const Linear& c) noexcept {
  px[0] = to_byte(linear_to_srgb(c.r));
  px[1] = to_byte(linear_to_srgb(c.g));
  px[2] = to_byte(linear_to_srgb(c.b));
}

void store_grey(std::uint8_t* px, const std::uint8_t* from) noexcept {
  const double luma = (0.2126 * from[0] + 0.7152 * from[1] + 0.0722 * from[2]) / 255;
  const std::uint8_t g = to_byte(0.18 + 0.5 * luma);
  px[0] = px[1] = px[2] = g;
}

}  // namespace raykernel::cli
