// 8-bit RGB images and PNG output (libpng).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::cli {

// Rows from top to bottom, 3 bytes (R, G, B) per pixel.
struct Image {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgb;

  Image() = default;
  Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), rgb(std::size_t{w} * h * 3, 0) {}
  [[nodiscard]] std::uint8_t* pixel(std::uint32_t x, std::uint32_t row) noexcept {
    return rgb.data() + (std::size_t{row} * width + x) * 3;
  }
  [[nodiscard]] const std::uint8_t* pixel(std::uint32_t x, std::uint32_t row) const noexcept {
    return rgb.data() + (std::size_t{row} * width + x) * 3;
  }
};

// `image` as the bytes of an 8-bit RGB PNG file, or the reason it cannot be encoded (an empty or malformed
// image, a libpng error) in `error`.
[[nodiscard]] std::vector<std::uint8_t> encode_png(const Image& image, std::string& error);

// Writes `image` as an 8-bit RGB PNG to `path`. Returns the reason on failure ("cannot create 'PATH':
// REASON", a libpng error, "cannot write 'PATH': REASON"), nothing on success.
[[nodiscard]] std::optional<std::string> write_png(const std::string& path, const Image& image);

// Reads an 8-bit RGB PNG (as write_png writes it), for tests. Returns nothing on any failure.
[[nodiscard]] std::optional<Image> read_png(const std::string& path);

}  // namespace raykernel::cli
