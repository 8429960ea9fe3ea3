// The double instantiations of the transform formulas (raykernel/transform.hpp), with the checks that
// make a bad transform an error instead of a silently wrong ray.
#include <raykernel/transform.hpp>

#include "core/format.hpp"
#include "camera/transform_internal.hpp"
#include "core/fp_environment.hpp"
#include "core/validation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace raykernel {

using detail::normalized_in_default_environment;
using detail::transform_direction_in_default_environment;
using detail::transform_point_in_default_environment;
using detail::transform_ray_in_default_environment;

namespace {

using formulas::Matrix4;
using formulas::Vector3;
using formulas::Vector4;

Vector3<double> to_array(const Vec3& v) noexcept { return {v.x, v.y, v.z}; }
Vec3 to_vec(const Vector3<double>& a) noexcept { return {a[0], a[1], a[2]}; }

using detail::is_zero;
bool finite(const Vec3& v) noexcept { return detail::is_finite(v); }

std::string describe(const Vec3& v) { return detail::shortest_text(v); }

}  // namespace

// The bodies of the public functions, which run them in the default floating-point environment
// (fp_environment.hpp) once, however deeply they call each other.
Vec3 detail::normalized_in_default_environment(const Vec3& v) {
  if (!finite(v)) throw invalid_input("cannot normalize " + describe(v) + ": not finite");
  const double scale = std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
  if (scale == 0) throw invalid_input("cannot normalize the zero vector");
  // Dividing by the largest component first keeps the squares away from overflow and underflow.
  const Vec3 s{v.x / scale, v.y / scale, v.z / scale};
  const double length = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
  return {s.x / length, s.y / length, s.z / length};
}

namespace {

Transform rotation_impl(const Vec3& axis, double radians) {
  const Vec3 a = normalized_in_default_environment(axis);
  const double c = std::cos(radians), s = std::sin(radians), k = 1 - c;
  // Rodrigues' formula: R = c·I + s·[a]× + (1 − c)·a aᵀ.
  return {{{{c + k * a.x * a.x, k * a.x * a.y - s * a.z, k * a.x * a.z + s * a.y, 0},
            {k * a.y * a.x + s * a.z, c + k * a.y * a.y, k * a.y * a.z - s * a.x, 0},
            {k * a.z * a.x - s * a.y, k * a.z * a.y + s * a.x, c + k * a.z * a.z, 0},
            {0, 0, 0, 1}}}};
}

Transform inverse_impl(const Transform& t) {
  const formulas::Adjugate<double> adj = formulas::adjugate(t.m);
  if (adj.determinant == 0 || !std::isfinite(adj.determinant))
    throw invalid_input(adj.determinant == 0 ? "transform is singular (determinant 0): no inverse"
                                             : "transform determinant is not finite: no inverse");
  const Transform r{formulas::inverse_from_adjugate(adj)};
  for (const auto& row : r.m)
    for (double x : row)
      if (!std::isfinite(x)) throw invalid_input("transform inverse has a non-finite entry (nearly singular)");
  return r;
}

}  // namespace

Vec3 detail::transform_point_in_default_environment(const Transform& t, const Vec3& p) {
  if (!finite(p)) throw invalid_input("point " + describe(p) + " is not finite");
  const Vector4<double> h = formulas::homogeneous_point(t.m, to_array(p));
  if (h[3] == 0) throw invalid_input("point " + describe(p) + " maps to infinity (w = 0 after the transform)");
  const Vec3 r = to_vec(formulas::perspective_divide(h));
  if (!finite(r)) throw invalid_input("point " + describe(p) + " maps to a non-finite point");
  return r;
}

Vec3 detail::transform_direction_in_default_environment(const Transform& t, const Vec3& d) {
  if (!t.is_affine())
    throw invalid_input(
        "a direction cannot go through a perspective transform (bottom row is not 0 0 0 1): transform two "
        "points and take their difference, as transform_ray does");
  if (!finite(d)) throw invalid_input("direction " + describe(d) + " is not finite");
  const Vec3 r = to_vec(formulas::transform_direction(t.m, to_array(d)));
  if (!finite(r)) throw invalid_input("direction " + describe(d) + " maps to a non-finite direction");
  return r;
}

Ray detail::transform_ray_in_default_environment(const Transform& t, const Ray& ray, Renormalize renormalize) {
  if (!detail::is_valid(ray)) throw invalid_input(*validate(ray));
  Ray r;
  if (t.is_affine()) {
    r.origin = transform_point_in_default_environment(t, ray.origin);
    r.direction = transform_direction_in_default_environment(t, ray.direction);
  } else {
    const formulas::ProjectedRay<double> p =
        formulas::project_ray_as_two_points(t.m, to_array(ray.origin), to_array(ray.direction));
    const double wo = p.origin_h[3], we = p.end_h[3];
    if (wo == 0 || we == 0 || (wo < 0) != (we < 0))
      throw invalid_input("ray crosses the plane w = 0 of the perspective transform between o and o + d "
                          "(w = " + detail::shortest_text(wo) + " and " + detail::shortest_text(we) + "): its image is not a ray");
    r.origin = to_vec(p.origin);
    r.direction = to_vec(p.direction);
    if (!finite(r.origin) || !finite(r.direction)) throw invalid_input("ray maps to a non-finite ray");
  }
  if (is_zero(r.direction)) throw invalid_input("ray direction maps to the zero vector");
  if (renormalize == Renormalize::yes) r.direction = normalized_in_default_environment(r.direction);
  return r;
}

namespace {

Transform camera_to_world_impl(const Vec3& eye, const Vec3& target, const Vec3& up) {
  if (!finite(eye) || !finite(target) || !finite(up)) throw invalid_input("camera eye, target and up must be finite");
  const Vec3 back{eye.x - target.x, eye.y - target.y, eye.z - target.z};
  if (is_zero(back)) throw invalid_input("camera eye and target are the same point");
  if (is_zero(up)) throw invalid_input("camera up is the zero vector");
  const Vec3 w = normalized_in_default_environment(back);
  const Vector3<double> side = formulas::cross(to_array(up), to_array(w));
  if (is_zero(to_vec(side))) throw invalid_input("camera up is parallel to the view direction");
  const Vec3 u = normalized_in_default_environment(to_vec(side));
  const Vec3 v = to_vec(formulas::cross(to_array(w), to_array(u)));
  return {{{{u.x, v.x, w.x, eye.x}, {u.y, v.y, w.y, eye.y}, {u.z, v.z, w.z, eye.z}, {0, 0, 0, 1}}}};
}

Transform perspective_projection_impl(double l, double r, double b, double t, double n, double f) {
  if (!(std::isfinite(l) && std::isfinite(r) && std::isfinite(b) && std::isfinite(t) && std::isfinite(n) &&
        std::isfinite(f)))
    throw invalid_input("perspective projection: every bound must be finite");
  if (l == r || b == t) throw invalid_input("perspective projection: empty near-plane window");
  if (!(0 < n && n < f)) throw invalid_input("perspective projection: needs 0 < near < far");
  return {{{{2 * n / (r - l), 0, (r + l) / (r - l), 0},
            {0, 2 * n / (t - b), (t + b) / (t - b), 0},
            {0, 0, -(f + n) / (f - n), -2 * f * n / (f - n)},
            {0, 0, -1, 0}}}};
}

}  // namespace

Transform Transform::identity() noexcept {
  return {{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}}};
}

Transform Transform::translation(const Vec3& o) noexcept {
  return {{{{1, 0, 0, o.x}, {0, 1, 0, o.y}, {0, 0, 1, o.z}, {0, 0, 0, 1}}}};
}

Transform Transform::scaling(const Vec3& f) noexcept {
  return {{{{f.x, 0, 0, 0}, {0, f.y, 0, 0}, {0, 0, f.z, 0}, {0, 0, 0, 1}}}};
}

Transform Transform::rotation(const Vec3& axis, double radians) {
  return detail::in_default_fp_environment([&] { return rotation_impl(axis, radians); });
}


Transform operator*(const Transform& a, const Transform& b) noexcept {
  return detail::in_default_fp_environment([&]() -> Transform { return {formulas::multiply(a.m, b.m)}; });
}

Transform inverse(const Transform& t) {
  return detail::in_default_fp_environment([&] { return inverse_impl(t); });
}

Vec3 transform_point(const Transform& t, const Vec3& p) {
  return detail::in_default_fp_environment([&] { return transform_point_in_default_environment(t, p); });
}

Vec3 transform_direction(const Transform& t, const Vec3& d) {
  return detail::in_default_fp_environment([&] { return transform_direction_in_default_environment(t, d); });
}

Ray transform_ray(const Transform& t, const Ray& ray, Renormalize renormalize) {
  return detail::in_default_fp_environment([&] { return transform_ray_in_default_environment(t, ray, renormalize); });
}

Vec3 normalized(const Vec3& v) {
  return detail::in_default_fp_environment([&] { return normalized_in_default_environment(v); });
}

Transform camera_to_world(const Vec3& eye, const Vec3& target, const Vec3& up) {
  return detail::in_default_fp_environment([&] { return camera_to_world_impl(eye, target, up); });
}

Transform perspective_projection(double l, double r, double b, double t, double n, double f) {
  return detail::in_default_fp_environment([&] { return perspective_projection_impl(l, r, b, t, n, f); });
}

}  // namespace raykernel
