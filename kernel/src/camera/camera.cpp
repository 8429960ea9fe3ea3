// Ray generation (docs/ray-casting.md §1.3) from the templated formulas of raykernel/transform.hpp, and reproducible
// stratified samples.
#include <raykernel/camera.hpp>

#include "core/fp_environment.hpp"
#include "camera/transform_internal.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

namespace raykernel {
namespace {

void check_pixel(std::uint32_t i, std::uint32_t j, ImageSize image) {
  if (image.width == 0 || image.height == 0) throw invalid_input("image size must be positive");
  if (i >= image.width || j >= image.height)
    throw invalid_input("pixel (" + std::to_string(i) + ", " + std::to_string(j) + ") is outside the " +
                        std::to_string(image.width) + "x" + std::to_string(image.height) + " image");
}

void check_window(const NearPlaneWindow& w) {
  if (!(std::isfinite(w.left) && std::isfinite(w.right) && std::isfinite(w.bottom) && std::isfinite(w.top) &&
        std::isfinite(w.near)))
    throw invalid_input("near-plane window: every bound must be finite");
  if (w.left == w.right || w.bottom == w.top) throw invalid_input("near-plane window is empty");
}

formulas::Vector3<double> window_point(const NearPlaneWindow& w, std::uint32_t i, std::uint32_t j, ImageSize image,
                                       PixelSample s) {
  return formulas::near_plane_point<double>(w.left, w.right, w.bottom, w.top, w.near, i, j, image.width,
                                            image.height, s.x, s.y);
}

// SplitMix64's output function (Steele, Lea, Flood 2014) as a stateless mixer.
std::uint64_t mix(std::uint64_t z) noexcept {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class SampleStream {
 public:
  explicit SampleStream(std::uint64_t state) noexcept : state_(state) {}
  std::uint64_t next() noexcept { return mix(state_ += 0x9e3779b97f4a7c15ULL); }
  // Uniform in [0, 1): the top 53 bits.
  double unit() noexcept { return static_cast<double>(next() >> 11) * 0x1p-53; }
  std::uint32_t below(std::uint32_t n) noexcept { return static_cast<std::uint32_t>((next() >> 32) * n >> 32); }

 private:
  std::uint64_t state_;
};

// (k + ξ)/count, kept below 1 (the rounding of k + ξ can reach k + 1).
double stratum_position(std::uint32_t k, double jitter, std::uint32_t count) noexcept {
  const double x = (k + jitter) / count;
  return x < 1 ? x : std::nextafter(1.0, 0.0);
}

}  // namespace

// The bodies of the public functions, which run them in the default floating-point environment
// (fp_environment.hpp) once, however deeply they call each other.
namespace {

Ray ndc_ray_impl(std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s) {
  check_pixel(i, j, image);
  const auto o = formulas::ndc_ray_origin<double>(i, j, image.width, image.height, s.x, s.y);
  return {{o[0], o[1], o[2]}, {0, 0, 1}};
}

Ray perspective_ray_impl(const NearPlaneWindow& w, std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s,
                    RayStart start) {
  check_pixel(i, j, image);
  check_window(w);
  if (!(w.near > 0)) throw invalid_input("perspective camera: near must be positive");
  const auto o = window_point(w, i, j, image, s);
  const Vec3 point{o[0], o[1], o[2]};
  const Vec3 direction = detail::normalized_in_default_environment(point);  // o/‖o‖: from the eye through the window point
  return {start == RayStart::eye ? Vec3{0, 0, 0} : point, direction};
}

Ray orthographic_ray_impl(const NearPlaneWindow& w, std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s) {
  check_pixel(i, j, image);
  check_window(w);
  const auto o = window_point(w, i, j, image, s);
  return {{o[0], o[1], o[2]}, {0, 0, -1}};
}

NearPlaneWindow window_from_field_of_view_impl(double fov_degrees, double aspect, double near) {
  if (!(fov_degrees > 0 && fov_degrees < 180)) throw invalid_input("field of view must be in (0, 180) degrees");
  if (!(aspect > 0 && std::isfinite(aspect))) throw invalid_input("aspect ratio must be positive and finite");
  if (!(near > 0 && std::isfinite(near))) throw invalid_input("near must be positive and finite");
  const double top = near * std::tan(fov_degrees * std::numbers::pi / 360);
  const double right = top * aspect;
  return {-right, right, -top, top, near};
}

std::vector<PixelSample> stratified_samples_impl(std::uint32_t count, std::uint64_t seed, std::uint32_t i, std::uint32_t j) {
  if (count == 0) throw invalid_input("samples per pixel must be positive");
  if (count == 1) return {PixelSample{}};
  SampleStream stream(mix(seed ^ mix((std::uint64_t{i} << 32) | j)));
  std::vector<std::uint32_t> row(count);
  for (std::uint32_t k = 0; k < count; ++k) row[k] = k;
  for (std::uint32_t k = count - 1; k > 0; --k) std::swap(row[k], row[stream.below(k + 1)]);  // Fisher–Yates
  std::vector<PixelSample> samples(count);
  for (std::uint32_t k = 0; k < count; ++k) {
    samples[k].x = stratum_position(k, stream.unit(), count);
    samples[k].y = stratum_position(row[k], stream.unit(), count);
  }
  return samples;
}

Ray camera_ray_impl(const Camera& camera, std::uint32_t i, std::uint32_t j, PixelSample s) {
  const Ray local = camera.projection == Projection::perspective
                        ? perspective_ray_impl(camera.window, i, j, camera.image, s, camera.start)
                        : orthographic_ray_impl(camera.window, i, j, camera.image, s);
  return detail::transform_ray_in_default_environment(camera.to_world, local, Renormalize::yes);
}

}  // namespace

Ray ndc_ray(std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s) {
  return detail::in_default_fp_environment([&] { return ndc_ray_impl(i, j, image, s); });
}

Ray perspective_ray(const NearPlaneWindow& w, std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s,
                    RayStart start) {
  return detail::in_default_fp_environment([&] { return perspective_ray_impl(w, i, j, image, s, start); });
}

Ray orthographic_ray(const NearPlaneWindow& w, std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s) {
  return detail::in_default_fp_environment([&] { return orthographic_ray_impl(w, i, j, image, s); });
}

NearPlaneWindow window_from_field_of_view(double fov_degrees, double aspect, double near) {
  return detail::in_default_fp_environment([&] { return window_from_field_of_view_impl(fov_degrees, aspect, near); });
}

std::vector<PixelSample> stratified_samples(std::uint32_t count, std::uint64_t seed, std::uint32_t i, std::uint32_t j) {
  return detail::in_default_fp_environment([&] { return stratified_samples_impl(count, seed, i, j); });
}

Ray Camera::ray(std::uint32_t i, std::uint32_t j, PixelSample s) const {
  return detail::in_default_fp_environment([&] { return camera_ray_impl(*this, i, j, s); });
}

}  // namespace raykernel
