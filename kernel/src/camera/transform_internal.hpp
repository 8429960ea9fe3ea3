// The transform routines without their own floating-point environment scope, for callers already inside
// one (camera.cpp): the public functions of raykernel/transform.hpp wrap these in one scope each.
#pragma once

#include <raykernel/transform.hpp>

namespace raykernel::detail {

[[nodiscard]] Vec3 normalized_in_default_environment(const Vec3& v);
[[nodiscard]] Vec3 transform_point_in_default_environment(const Transform& t, const Vec3& p);
[[nodiscard]] Vec3 transform_direction_in_default_environment(const Transform& t, const Vec3& d);
[[nodiscard]] Ray transform_ray_in_default_environment(const Transform& t, const Ray& ray, Renormalize renormalize);

}  // namespace raykernel::detail
