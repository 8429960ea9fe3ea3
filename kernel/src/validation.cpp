// The reasons of validate (raykernel.hpp), worded once for every entry point and the CLI.
#include "validation.hpp"

namespace raykernel {
namespace detail {

std::optional<std::string> non_finite_reason(const char* name, const Vec3& v) {
  const double component[3] = {v.x, v.y, v.z};
  for (int i = 0; i < 3; ++i) {
    if (is_finite(component[i])) continue;
    const char* what = component[i] != component[i] ? "NaN" : (component[i] > 0 ? "+inf" : "-inf");
    return std::string(name) + " " + "xyz"[i] + " is " + what;
  }
  return std::nullopt;
}

}  // namespace detail

std::optional<std::string> validate(const Ray& ray) {
  if (auto reason = detail::non_finite_reason("ray origin", ray.origin)) return reason;
  if (auto reason = detail::non_finite_reason("ray direction", ray.direction)) return reason;
  if (detail::is_zero(ray.direction)) return std::string("ray direction is the zero vector");
  return std::nullopt;
}

std::optional<std::string> validate(const Plane& plane) {
  if (auto reason = detail::non_finite_reason("plane point", plane.point)) return reason;
  if (auto reason = detail::non_finite_reason("plane normal", plane.normal)) return reason;
  if (detail::is_zero(plane.normal)) return std::string("plane normal is the zero vector");
  return std::nullopt;
}

// Every non-finite component first, in the order of the query's text (docs/contract.md §3), then the zero
// vectors.
std::optional<std::string> validate(const Ray& ray, const Plane& plane) {
  if (auto reason = detail::non_finite_reason("ray origin", ray.origin)) return reason;
  if (auto reason = detail::non_finite_reason("ray direction", ray.direction)) return reason;
  if (auto reason = detail::non_finite_reason("plane point", plane.point)) return reason;
  if (auto reason = detail::non_finite_reason("plane normal", plane.normal)) return reason;
  if (detail::is_zero(ray.direction)) return std::string("ray direction is the zero vector");
  if (detail::is_zero(plane.normal)) return std::string("plane normal is the zero vector");
  return std::nullopt;
}

}  // namespace raykernel
