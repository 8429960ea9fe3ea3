// PNG output with libpng's simplified API (png_image_write_to_memory / png_image_finish_read), which reports
// errors in a message instead of longjmp.
#include "rendering/png_image.hpp"

#include "common/text_format.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace raykernel::cli {

std::vector<std::uint8_t> encode_png(const Image& image, std::string& error) {
  error.clear();
  if (image.width == 0 || image.height == 0 || image.rgb.size() != std::size_t{image.width} * image.height * 3) {
    error = "empty or malformed image";
    return {};
  }
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGB;
  png_alloc_size_t size = 0;
  std::vector<std::uint8_t> bytes;
  // The first call measures, the second writes.
  if (png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), 0, nullptr)) {
    bytes.resize(size);
    if (png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), 0, nullptr)) {
      bytes.resize(size);
      return bytes;
    }
  }
  error = std::string("cannot encode PNG: ") + png.message;
  png_image_free(&png);
  return {};
}

std::optional<std::string> write_png(const std::string& path, const Image& image) {
  std::string error;
  const std::vector<std::uint8_t> bytes = encode_png(image, error);
  if (!error.empty()) return error;
  // Open first, so that an unwritable path gives the system's reason.
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return "cannot create '" + printable(path) + "': " + std::strerror(errno);
  const bool written = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  const int write_errno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) return "cannot write '" + printable(path) + "': " + std::strerror(written ? errno : write_errno);
  return std::nullopt;
}

std::optional<Image> read_png(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) return std::nullopt;
  png.format = PNG_FORMAT_RGB;
  Image image(png.width, png.height);
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) {
    png_image_free(&png);
    return std::nullopt;
  }
  return image;
}

}  // namespace raykernel::cli
