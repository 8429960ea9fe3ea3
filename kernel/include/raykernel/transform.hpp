// raykernel/transform.hpp: 4×4 homogeneous transforms of points, directions and rays (docs/ray-casting.md §1.4).
//
// A point is the homogeneous column (x, y, z, 1): it is multiplied by the matrix and divided by the
// resulting w (the perspective divide). A direction is (x, y, z, 0): translation leaves it alone, which is
// right only for affine matrices (bottom row exactly 0 0 0 1); through a perspective matrix a direction has
// no meaning of its own, and `transform_direction` refuses it. A ray goes through an affine transform as
// origin-as-point and direction-as-direction; through a perspective transform as the difference of two
// transformed points, o and o + d, which is what the seed recommends for rays leaving NDC.
//
//   using namespace raykernel;
//   const Transform to_world = Transform::translation({2, 3, 4});
//   transform_point(to_world, {5, 1, 1});       // (7, 4, 5)
//   transform_direction(to_world, {1, 0, 0});   // (1, 0, 0): directions ignore translation
//   const Ray r = transform_ray(to_world, {{5, 1, 1}, {1, 0, 0}});  // {(7, 4, 5), (1, 0, 0)}
//
// Each formula is written once, in namespace `formulas`, templated on the number type, and the double API
// below instantiates it; tests evaluate the same templates in exact rationals. These are ordinary
// floating-point computations (a few roundings each), not certified predicates: the exactness of
// raykernel is in what it decides about the rays these functions produce.
#pragma once

#include <raykernel/raykernel.hpp>

#include <array>
#include <cstddef>

namespace raykernel {

namespace formulas {

template <class T>
using Vector3 = std::array<T, 3>;
template <class T>
using Vector4 = std::array<T, 4>;
// Row-major: m[row][column]; it multiplies column vectors, M·v.
template <class T>
using Matrix4 = std::array<std::array<T, 4>, 4>;

// M·v, each row evaluated left to right: ((m_r0·v_0 + m_r1·v_1) + m_r2·v_2) + m_r3·v_3.
template <class T>
[[nodiscard]] Vector4<T> multiply(const Matrix4<T>& m, const Vector4<T>& v) {
  Vector4<T> r;
  for (std::size_t row = 0; row < 4; ++row)
    r[row] = ((m[row][0] * v[0] + m[row][1] * v[1]) + m[row][2] * v[2]) + m[row][3] * v[3];
  return r;
}

// A·B, each entry evaluated left to right as above.
template <class T>
[[nodiscard]] Matrix4<T> multiply(const Matrix4<T>& a, const Matrix4<T>& b) {
  Matrix4<T> r;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j)
      r[i][j] = ((a[i][0] * b[0][j] + a[i][1] * b[1][j]) + a[i][2] * b[2][j]) + a[i][3] * b[3][j];
  return r;
}

// The homogeneous image of the point p: M·(p, 1).
template <class T>
[[nodiscard]] Vector4<T> homogeneous_point(const Matrix4<T>& m, const Vector3<T>& p) {
  return multiply(m, Vector4<T>{p[0], p[1], p[2], T(1)});
}

// (X/W, Y/W, Z/W): the perspective divide. W must be nonzero (the callers check). For an affine M,
// W = 0·x + 0·y + 0·z + 1·1 = 1 exactly and the divide changes nothing.
template <class T>
[[nodiscard]] Vector3<T> perspective_divide(const Vector4<T>& h) {
  if (h[3] == 1) return {h[0], h[1], h[2]};  // x/1 = x exactly: an affine transform needs no division
  return {h[0] / h[3], h[1] / h[3], h[2] / h[3]};
}

// The image of the direction d: the first three rows of M·(d, 0) (docs/ray-casting.md §1.4: M(o + d) − M(o) = M·(d, 0)).
template <class T>
[[nodiscard]] Vector3<T> transform_direction(const Matrix4<T>& m, const Vector3<T>& d) {
  const Vector4<T> h = multiply(m, Vector4<T>{d[0], d[1], d[2], T(0)});
  return {h[0], h[1], h[2]};
}

// A ray through a perspective M as two points: h_o = M·(o, 1) and h_e = h_o + M·(d, 0) = M·(o + d, 1)
// (linearity, without rounding o + d first); the new origin is h_o divided, the new direction the
// difference h_e/W_e − h_o/W_o.
template <class T>
struct ProjectedRay {
  Vector4<T> origin_h, end_h;  // homogeneous images of o and o + d
  Vector3<T> origin, direction;
};
template <class T>
[[nodiscard]] ProjectedRay<T> project_ray_as_two_points(const Matrix4<T>& m, const Vector3<T>& o, const Vector3<T>& d) {
  ProjectedRay<T> r;
  r.origin_h = homogeneous_point(m, o);
  const Vector4<T> dh = multiply(m, Vector4<T>{d[0], d[1], d[2], T(0)});
  for (std::size_t k = 0; k < 4; ++k) r.end_h[k] = r.origin_h[k] + dh[k];
  r.origin = perspective_divide(r.origin_h);
  const Vector3<T> end = perspective_divide(r.end_h);
  r.direction = {end[0] - r.origin[0], end[1] - r.origin[1], end[2] - r.origin[2]};
  return r;
}

// Seed §1.3, NDC: the ray origin for the sample (s_x, s_y) of pixel (i, j) of an m × n image,
// (2(i + s_x)/m − 1, 2(j + s_y)/n − 1, −1); the pixel centre is s = (½, ½). The direction is (0, 0, 1).
template <class T>
[[nodiscard]] Vector3<T> ndc_ray_origin(const T& i, const T& j, const T& m, const T& n, const T& sx, const T& sy) {
  return {T(2) * (i + sx) / m - T(1), T(2) * (j + sy) / n - T(1), T(-1)};
}

// Seed §1.3, camera space: the point of the near-plane window [l, r] × [b, t] at z = −near for the sample
// (s_x, s_y) of pixel (i, j): (l + (i + s_x)/m·(r − l), b + (j + s_y)/n·(t − b), −near).
template <class T>
[[nodiscard]] Vector3<T> near_plane_point(const T& left, const T& right, const T& bottom, const T& top, const T& near,
                                          const T& i, const T& j, const T& m, const T& n, const T& sx, const T& sy) {
  return {left + (i + sx) / m * (right - left), bottom + (j + sy) / n * (top - bottom), -near};
}

template <class T>
[[nodiscard]] Vector3<T> cross(const Vector3<T>& a, const Vector3<T>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The 3×3 determinant of the rows r0, r1, r2 restricted to the columns c0, c1, c2 (cofactor expansion
// along the first row).
template <class T>
[[nodiscard]] T minor3(const Matrix4<T>& m, std::size_t r0, std::size_t r1, std::size_t r2, std::size_t c0,
                       std::size_t c1, std::size_t c2) {
  return (m[r0][c0] * (m[r1][c1] * m[r2][c2] - m[r1][c2] * m[r2][c1]) -
          m[r0][c1] * (m[r1][c0] * m[r2][c2] - m[r1][c2] * m[r2][c0])) +
         m[r0][c2] * (m[r1][c0] * m[r2][c1] - m[r1][c1] * m[r2][c0]);
}

// The adjugate (transposed cofactor matrix) and the determinant: M⁻¹ = adj(M)/det(M).
template <class T>
struct Adjugate {
  Matrix4<T> adjugate;
  T determinant;
};
template <class T>
[[nodiscard]] Adjugate<T> adjugate(const Matrix4<T>& m) {
  Adjugate<T> r;
  auto others = [](std::size_t k) {
    std::array<std::size_t, 3> o{};
    std::size_t n = 0;
    for (std::size_t x = 0; x < 4; ++x)
      if (x != k) o[n++] = x;
    return o;
  };
  for (std::size_t i = 0; i < 4; ++i) {
    const auto rows = others(i);
    for (std::size_t j = 0; j < 4; ++j) {
      const auto cols = others(j);
      const T minor = minor3(m, rows[0], rows[1], rows[2], cols[0], cols[1], cols[2]);
      r.adjugate[j][i] = ((i + j) % 2 == 0) ? minor : T(-minor);  // cofactor C_ij goes to entry (j, i)
    }
  }
  r.determinant = ((m[0][0] * r.adjugate[0][0] + m[0][1] * r.adjugate[1][0]) + m[0][2] * r.adjugate[2][0]) +
                  m[0][3] * r.adjugate[3][0];
  return r;
}

// M⁻¹ = adj(M)/det(M), entry by entry (det must be nonzero: the callers check).
template <class T>
[[nodiscard]] Matrix4<T> inverse_from_adjugate(const Adjugate<T>& a) {
  Matrix4<T> r;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) r[i][j] = a.adjugate[i][j] / a.determinant;
  return r;
}

}  // namespace formulas

// ---------------------------------------------------------------------------------------------------------
// The double API.

// A 4×4 homogeneous transform acting on column vectors (row-major storage: m[row][column]).
struct Transform {
  formulas::Matrix4<double> m;

  [[nodiscard]] static Transform identity() noexcept;
  [[nodiscard]] static Transform translation(const Vec3& offset) noexcept;
  [[nodiscard]] static Transform scaling(const Vec3& factors) noexcept;
  // Rotation by `radians` about `axis` (any nonzero length; right-handed: counter-clockwise looking
  // against the axis). Throws invalid_input for a zero or non-finite axis.
  [[nodiscard]] static Transform rotation(const Vec3& axis, double radians);

  // Bottom row exactly (0, 0, 0, 1): no perspective, so directions transform as (x, y, z, 0).
  [[nodiscard]] bool is_affine() const noexcept { return m[3][0] == 0 && m[3][1] == 0 && m[3][2] == 0 && m[3][3] == 1; }

  friend bool operator==(const Transform&, const Transform&) = default;
};

// a·b: apply b first, then a.
[[nodiscard]] Transform operator*(const Transform& a, const Transform& b) noexcept;

// The inverse, by the adjugate. Throws invalid_input when the determinant is zero or not finite, or an
// entry of the result is not finite.
[[nodiscard]] Transform inverse(const Transform& t);

// The point p through t: M·(p, 1), then divided by its w. Throws invalid_input when w is zero (p maps to
// infinity) or the result is not finite.
[[nodiscard]] Vec3 transform_point(const Transform& t, const Vec3& p);

// The direction d through an affine t: the first three rows of M·(d, 0). Throws invalid_input when t is
// not affine: a direction through a perspective transform depends on where it starts, so transform two
// points instead (transform_ray does).
[[nodiscard]] Vec3 transform_direction(const Transform& t, const Vec3& d);

enum class Renormalize : bool { no, yes };

// The ray through t. Affine t: origin as a point, direction as a direction. Perspective t: the origin o and
// the point o + d as points, and the direction as their difference (formulas::project_ray_as_two_points);
// both must have the same sign of w (the segment from o to o + d must not cross the plane w = 0, where
// the perspective divide flips). With Renormalize::yes the direction is scaled to unit length (scaling
// and shearing change it). Throws invalid_input when the result is not a valid ray (non-finite, zero
// direction) or the sign of w differs.
[[nodiscard]] Ray transform_ray(const Transform& t, const Ray& ray, Renormalize renormalize = Renormalize::no);

// v/‖v‖, computed without overflow or underflow (scaled by the largest component first). Throws
// invalid_input for a zero or non-finite v.
[[nodiscard]] Vec3 normalized(const Vec3& v);

// The camera-to-world transform of a camera at `eye` looking at `target` with `up` pointing roughly up
// (the camera looks down its −z axis, x to the right, y up): columns u, v, w, eye with
// w = (eye − target)/‖eye − target‖, u = (up × w)/‖up × w‖, v = w × u. Throws invalid_input when
// eye == target or up is parallel to the view direction.
[[nodiscard]] Transform camera_to_world(const Vec3& eye, const Vec3& target, const Vec3& up);

// The perspective projection (OpenGL's glFrustum) from camera space to homogeneous clip space for the
// near-plane window [left, right] × [bottom, top] at z = −near and the far plane z = −far; after the
// divide the frustum is the NDC cube [−1, 1]³ (near → z = −1). Its inverse takes NDC rays to camera space.
// Throws invalid_input unless left ≠ right, bottom ≠ top and 0 < near < far.
[[nodiscard]] Transform perspective_projection(double left, double right, double bottom, double top, double near,
                                               double far);

}  // namespace raykernel
