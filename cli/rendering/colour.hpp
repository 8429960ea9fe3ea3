// Colour for `raykernel render`: scene colours are display (sRGB) values; shading and averaging of samples
// happen in linear light; pixels are 8-bit sRGB.
#pragma once

#include "scenes/scene.hpp"

#include <cstdint>

namespace raykernel::cli {

// A colour in linear light.
struct Linear {
  double r = 0, g = 0, b = 0;
  Linear& operator+=(const Linear& o) noexcept {
    r += o.r, g += o.g, b += o.b;
    return *this;
  }
};
[[nodiscard]] inline Linear operator*(const Linear& c, double k) noexcept { return {c.r * k, c.g * k, c.b * k}; }
[[nodiscard]] inline Linear operator+(const Linear& a, const Linear& b) noexcept {
  return {a.r + b.r, a.g + b.g, a.b + b.b};
}

// A scene colour in linear light (the sRGB transfer function, IEC 61966-2-1).
[[nodiscard]] Linear linear(const Rgb& display) noexcept;

// Writes `c` (clamped to [0, 1]) as 8-bit sRGB to the three bytes at `px`.
void store(std::uint8_t* px, const Linear& c) noexcept;

// Writes a dimmed grey of the pixel `from` to `px`: the background of the diagnostic images, on which the
// coloured markers stand out.
void store_grey(std::uint8_t* px, const std::uint8_t* from) noexcept;

}  // namespace raykernel::cli
