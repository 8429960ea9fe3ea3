// PNG output with libpng's simplified API (png_image_write_to_file / png_image_finish_read), which reports
// errors in a message instead of longjmp.
#include "png_image.hpp"

#include <png.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace raykernel::cli {

std::optional<std::string> write_png(const std::string& path, const Image& image) {
  if (image.width == 0 || image.height == 0 || image.rgb.size() != std::size_t{image.width} * image.height * 3)
    return std::string("empty or malformed image");
  // Open first, so that an unwritable path gives the system's reason.
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return std::string("cannot create '") + path + "': " + std::strerror(errno);
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = image.width;
  png.height = image.height;
  png.format = PNG_FORMAT_RGB;
  const int ok = png_image_write_to_stdio(&png, f, 0, image.rgb.data(), 0, nullptr);
  const bool closed = std::fclose(f) == 0;
  if (!ok) {
    std::string reason = std::string("cannot write PNG '") + path + "': " + png.message;
    png_image_free(&png);
    return reason;
  }
  if (!closed) return std::string("cannot write '") + path + "': " + std::strerror(errno);
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
