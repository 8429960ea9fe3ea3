// The reasons of validate (raykernel.hpp, triangle.hpp), worded once for every entry point and the CLI.
#include "core/validation.hpp"

#include "core/fp_environment.hpp"

#include <raykernel/triangle.hpp>

#include <bit>
#include <cstdint>

namespace raykernel {
namespace detail {

std::optional<std::string> non_finite_reason(const char* name, const Vec3& v) {
  const double component[3] = {v.x, v.y, v.z};
  for (int i = 0; i < 3; ++i) {
    if (is_finite(component[i])) continue;
    // From the bits, as is_finite: no comparison, which a signaling NaN would answer by raising "invalid".
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(component[i]);
    const char* what = (bits << 12) != 0 ? "NaN" : ((bits >> 63) == 0 ? "+inf" : "-inf");
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

// The ray first (its own reasons, as validate(ray) words them), then the vertices in the order of the query's
// text (docs/contract.md §6: o, d, a, b, c). A degenerate triangle is valid.
std::optional<std::string> validate(const Ray& ray, const Triangle& triangle) {
  return detail::in_default_fp_environment([&]() -> std::optional<std::string> {
    if (auto reason = validate(ray)) return reason;
    if (auto reason = detail::non_finite_reason("triangle vertex a", triangle.a)) return reason;
    if (auto reason = detail::non_finite_reason("triangle vertex b", triangle.b)) return reason;
    if (auto reason = detail::non_finite_reason("triangle vertex c", triangle.c)) return reason;
    return std::nullopt;
  });
}

}  // namespace raykernel
