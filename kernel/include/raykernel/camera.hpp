// raykernel/camera.hpp: the rays to cast for an image (docs/ray-casting.md §1.3).
//
// Pixel (i, j) of an m × n image is column i (0 at the left) and row j (0 at the BOTTOM, as in the seed,
// where y grows with j); an image file's first row is j = n − 1. A sample is a position (s_x, s_y) inside
// the pixel, each in [0, 1); the pixel centre is (½, ½), which is the seed's i + ½, j + ½.
//
//   NDC:          origin (2(i + s_x)/m − 1, 2(j + s_y)/n − 1, −1), direction (0, 0, 1)
//   perspective:  origin on the near-plane window (l + (i + s_x)/m·(r − l), b + (j + s_y)/n·(t − b), −near)
//                 (or at the eye, (0, 0, 0)), direction o/‖o‖ (unit length, away from the eye)
//   orthographic: origin on the window as above, direction (0, 0, −1)
//
// Camera space looks down −z with x to the right and y up; `Camera` adds the camera-to-world transform
// (transform.hpp: camera_to_world from eye, target and up), so `Camera::ray` returns world-space rays.
// Supersampling: `stratified_samples` gives reproducible jittered sample positions (the seed mentions
// "several ray origin locations per pixel"); averaging the samples' colours is the renderer's job.
//
//   using namespace raykernel;
//   const Camera camera = Camera::perspective(camera_to_world({0, 1.6, 6}, {0, 0.8, 0}, {0, 1, 0}),
//                                             window_from_field_of_view(50, 16.0 / 9, 0.1), {640, 360});
//   for (const PixelSample& s : stratified_samples(4, /*seed=*/1, i, j))
//     if (const auto hit = nearest_hit(camera.ray(i, j, s), planes)) ...
#pragma once

#include <raykernel/raykernel.hpp>
#include <raykernel/transform.hpp>

#include <cstdint>
#include <vector>

namespace raykernel {

struct ImageSize {
  std::uint32_t width;   // m, pixels per row
  std::uint32_t height;  // n, rows
};

// A position inside a pixel, each coordinate in [0, 1); (½, ½) is the centre.
struct PixelSample {
  double x = 0.5;
  double y = 0.5;
};

// The near-plane window of a camera: x from left to right and y from bottom to top at z = −near.
struct NearPlaneWindow {
  double left, right, bottom, top, near;
};

// The NDC ray of docs/ray-casting.md §1.3 for sample s of pixel (i, j). Throws invalid_input when the pixel is outside
// the image or the image is empty.
[[nodiscard]] Ray ndc_ray(std::uint32_t i, std::uint32_t j, ImageSize image, PixelSample s = {});

enum class RayStart : bool {
  near_plane,  // the origin is the point on the near-plane window (the seed's first choice)
  eye,         // the origin is the eye, (0, 0, 0); the direction is the same
};

// The camera-space perspective ray of docs/ray-casting.md §1.3: direction o/‖o‖ where o is the near-plane point. Throws
// invalid_input for a pixel outside the image, near ≤ 0, or an empty window.
[[nodiscard]] Ray perspective_ray(const NearPlaneWindow& window, std::uint32_t i, std::uint32_t j, ImageSize image,
                                  PixelSample s = {}, RayStart start = RayStart::near_plane);

// The camera-space orthographic ray: origin on the near-plane window, direction (0, 0, −1).
[[nodiscard]] Ray orthographic_ray(const NearPlaneWindow& window, std::uint32_t i, std::uint32_t j, ImageSize image,
                                   PixelSample s = {});

// The window of a perspective camera with the given vertical field of view (degrees, in (0, 180)),
// aspect ratio width/height and near distance: top = near·tan(fov/2), right = top·aspect, symmetric.
[[nodiscard]] NearPlaneWindow window_from_field_of_view(double vertical_fov_degrees, double aspect, double near);

// `count` sample positions inside pixel (i, j), reproducible from (seed, i, j) and independent of the order
// pixels are visited in: count = 1 gives the centre; otherwise n-rooks stratification (Shirley 1991),
// sample k in column stratum k and row stratum π(k) of a random permutation π, jittered uniformly inside
// its cell, so each of the count columns and rows of the pixel holds exactly one sample.
[[nodiscard]] std::vector<PixelSample> stratified_samples(std::uint32_t count, std::uint64_t seed, std::uint32_t i,
                                                          std::uint32_t j);

enum class Projection : bool { perspective, orthographic };

// A camera: projection, near-plane window, image size and the camera-to-world transform.
struct Camera {
  Transform to_world;
  NearPlaneWindow window;
  ImageSize image;
  Projection projection = Projection::perspective;
  RayStart start = RayStart::near_plane;

  [[nodiscard]] static Camera perspective(const Transform& to_world, const NearPlaneWindow& window, ImageSize image) {
    return {to_world, window, image, Projection::perspective, RayStart::near_plane};
  }
  [[nodiscard]] static Camera orthographic(const Transform& to_world, const NearPlaneWindow& window, ImageSize image) {
    return {to_world, window, image, Projection::orthographic, RayStart::near_plane};
  }

  // The world-space ray for sample s of pixel (i, j): the camera-space ray through `to_world`
  // (transform_ray: origin as a point, direction as a direction, renormalized when to_world is affine and
  // the projection perspective, so that t is a distance).
  [[nodiscard]] Ray ray(std::uint32_t i, std::uint32_t j, PixelSample s = {}) const;
};

}  // namespace raykernel
