// Shading for `raykernel render`: what colour a ray's nearest hit (or miss) gets. Legible, not physical:
// the plane's colour or checker square, darkened at grazing angles, faded into the horizon colour with
// distance; a miss shows the sky.
#pragma once

#include "rendering/colour.hpp"
#include "scenes/scene.hpp"

#include <raykernel/mesh_queries.hpp>
#include <raykernel/nearest_hit.hpp>

#include <optional>
#include <vector>

namespace raykernel::cli {

class Shader {
 public:
  explicit Shader(const Scene& scene);

  // The colour, in linear light, of `ray` whose nearest hit is `hit` (nothing: a miss).
  [[nodiscard]] Linear shade(const Ray& ray, const std::optional<NearestHit>& hit) const noexcept;
  // The colour of `ray` hitting triangle `triangle` of scene.mesh at `t`: the mesh's colour, lit by the
  // triangle's normal as a plane is by its own.
  [[nodiscard]] Linear shade_triangle(const Ray& ray, std::uint32_t triangle, double t) const noexcept;
  // The colour of `ray` hitting sphere `sphere` of scene.spheres at `t`: its colour, lit by the normal at the hit.
  [[nodiscard]] Linear shade_sphere(const Ray& ray, std::size_t sphere, double t) const noexcept;

 private:
  // A plane's shading data: unit normal, checker axes in the plane, its one or two colours.
  struct PreparedPlane {
    Vec3 unit_normal;
    Vec3 u, v;
    Linear color[2];
    double checker_size = 0;  // 0: solid colour
  };
  static PreparedPlane prepare(const ScenePlane& plane);
  [[nodiscard]] Linear sky(const Vec3& unit_direction) const noexcept;
  // `base` lit at the angle between the ray and `unit_normal`, fogged by the distance t·|d|.
  [[nodiscard]] Linear lit(const Vec3& unit_direction, double length, double t, Linear base,
                           const Vec3& unit_normal) const noexcept;

  const Scene& scene_;
  std::vector<PreparedPlane> planes_;
  std::vector<Linear> mesh_colors_;
  std::vector<Linear> sphere_colors_;
  Linear horizon_, zenith_;
};

}  // namespace raykernel::cli
