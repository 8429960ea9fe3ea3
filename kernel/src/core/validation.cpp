// The reasons of validate (raykernel.hpp, triangle.hpp), worded once for every entry point and the CLI.
#include "core/validation.hpp"

#include "core/fp_environment.hpp"

#include <raykernel/occlusion.hpp>
#include <raykernel/sphere.hpp>
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

void throw_if_invalid_interval(const RayInterval& interval) {
  if (is_valid(interval)) [[likely]]
    return;
  throw invalid_input(*validate(interval));
}

}  // namespace detail

// Each bound's own problem first (t_min, then t_max), then their order; from the bits, as is_valid.
std::optional<std::string> validate(const RayInterval& interval) {
  auto problem = [](double x) -> const char* {
    const auto bits = std::bit_cast<std::uint64_t>(x);
    if (!detail::is_finite(x)) return (bits << 12) != 0 ? "is NaN" : ((bits >> 63) == 0 ? nullptr : "is -inf");
    return (bits >> 63) != 0 && !detail::is_zero(x) ? "is negative" : nullptr;
  };
  if (const char* p = problem(interval.t_min)) return std::string("t_min ") + p;
  if (!detail::is_finite(interval.t_min)) return std::string("t_min is +inf");
  if (const char* p = problem(interval.t_max)) return std::string("t_max ") + p;
  if (!detail::is_valid(interval)) return std::string("t_min is greater than t_max");
  return std::nullopt;
}

std::optional<std::string> validate_segment(const Vec3& p, const Vec3& q) {
  if (auto reason = detail::non_finite_reason("segment p", p)) return reason;
  if (auto reason = detail::non_finite_reason("segment q", q)) return reason;
  // Equal as values (0 equals −0), from the bits: equal patterns, or both zeros.
  auto same = [](double x, double y) {
    return std::bit_cast<std::uint64_t>(x) == std::bit_cast<std::uint64_t>(y) || (detail::is_zero(x) && detail::is_zero(y));
  };
  if (same(p.x, q.x) && same(p.y, q.y) && same(p.z, q.z)) return std::string("segment endpoints are equal (p = q)");
  return std::nullopt;
}

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

namespace detail {
namespace {
// The centre's and the radius's non-finite components, in that order.
std::optional<std::string> sphere_non_finite_reason(const Sphere& sphere) {
  if (auto reason = non_finite_reason("sphere center", sphere.center)) return reason;
  if (!is_finite(sphere.radius)) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(sphere.radius);
    return std::string("sphere radius is ") + ((bits << 12) != 0 ? "NaN" : ((bits >> 63) == 0 ? "+inf" : "-inf"));
  }
  return std::nullopt;
}
}  // namespace
}  // namespace detail

// Every non-finite component first, in the order of the query's text (docs/contract.md §10: o, d, c, r), then
// the zero direction, then a radius that is not positive (0, −0 and negative values, subnormals included).
std::optional<std::string> validate(const Ray& ray, const Sphere& sphere) {
  return detail::in_default_fp_environment([&]() -> std::optional<std::string> {
    if (auto reason = detail::non_finite_reason("ray origin", ray.origin)) return reason;
    if (auto reason = detail::non_finite_reason("ray direction", ray.direction)) return reason;
    if (auto reason = detail::sphere_non_finite_reason(sphere)) return reason;
    if (detail::is_zero(ray.direction)) return std::string("ray direction is the zero vector");
    if (!detail::is_positive(sphere.radius)) return std::string("sphere radius is not positive");
    return std::nullopt;
  });
}

// The sphere alone (a scene's spheres, SphereSet): the same reasons, in the same order.
std::optional<std::string> validate(const Sphere& sphere) {
  return detail::in_default_fp_environment([&]() -> std::optional<std::string> {
    if (auto reason = detail::sphere_non_finite_reason(sphere)) return reason;
    if (!detail::is_positive(sphere.radius)) return std::string("sphere radius is not positive");
    return std::nullopt;
  });
}

}  // namespace raykernel
