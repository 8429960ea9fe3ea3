// Rays and transforms (docs/ray-casting.md §1.3–1.4): the examples of the notes, hand-derived rays, the refusals, and
// RapidCheck properties comparing the double API with exact rational evaluation of the same templated
// formulas (raykernel/transform.hpp, namespace formulas): exact where binary64 is exact, and within the
// standard rounding-error bound (Higham, "Accuracy and Stability of Numerical Algorithms", §3.1:
// γ_k = k·u/(1 − k·u)) where it is not.
#include "support/oracle.hpp"

#include <raykernel/camera.hpp>
#include <raykernel/transform.hpp>

#include <gmpxx.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace raykernel {
namespace {

using formulas::Matrix4;
using formulas::Vector3;
using formulas::Vector4;

const mpq_class u_exact(mpz_class(1), mpz_class(1) << 53);
mpq_class gamma(int k) { return k * u_exact / (1 - k * u_exact); }

bool same(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
std::string show(const Vec3& v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "(%a, %a, %a)", v.x, v.y, v.z);
  return buf;
}

// Distance in ulps between two doubles of the same sign (for hand-derived values that involve one sqrt).
double ulps_apart(double a, double b) { return std::fabs(a - b) / (std::nextafter(std::fabs(b), HUGE_VAL) - std::fabs(b)); }

Matrix4<mpq_class> exact_matrix(const Transform& t) {
  Matrix4<mpq_class> m;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) m[i][j] = mpq_class(t.m[i][j]);
  return m;
}
Vector3<mpq_class> exact_vector(const Vec3& v) { return {mpq_class(v.x), mpq_class(v.y), mpq_class(v.z)}; }

// ---- The examples of docs/ray-casting.md §1.4 --------------------------------------------------------------------------

TEST(SeedExamples, TranslationMovesPointsButNotDirections) {
  // "consider a direction (1, 0, 0) pointing from ray origin (5, 1, 1) towards the point (6, 1, 1). Under a
  // translation by vector (2, 3, 4), these two points become (7, 4, 5) and (8, 4, 5) and the direction is
  // still (1, 0, 0)".
  const Transform t = Transform::translation({2, 3, 4});
  EXPECT_TRUE(same(transform_point(t, {5, 1, 1}), {7, 4, 5}));
  EXPECT_TRUE(same(transform_point(t, {6, 1, 1}), {8, 4, 5}));
  EXPECT_TRUE(same(transform_direction(t, {1, 0, 0}), {1, 0, 0}));
  const Ray r = transform_ray(t, {{5, 1, 1}, {1, 0, 0}});
  EXPECT_TRUE(same(r.origin, {7, 4, 5}));
  EXPECT_TRUE(same(r.direction, {1, 0, 0}));
  // "the direction has not been transformed to (3, 3, 4) adding (2, 3, 4) like we did with the points":
  // that is what treating it as a point would give.
  EXPECT_TRUE(same(transform_point(t, {1, 0, 0}), {3, 3, 4}));
}

TEST(SeedExamples, ADirectionIsTheDifferenceOfTwoTransformedPoints) {
  // M(o + d) − M(o) = M·(d, 0) for an affine M (docs/ray-casting.md §1.4), here a rotation-free shear and scale with
  // dyadic entries, so that every operation is exact.
  Transform m = Transform::identity();
  m.m = {{{2, 0.5, 0, 1}, {0, 1, -0.25, 2}, {0.125, 0, 4, -3}, {0, 0, 0, 1}}};
  const Vec3 o{5, 1, 1}, d{1, -2, 0.5};
  const Vec3 a = transform_point(m, o), b = transform_point(m, {o.x + d.x, o.y + d.y, o.z + d.z});
  EXPECT_TRUE(same(transform_direction(m, d), {b.x - a.x, b.y - a.y, b.z - a.z}));
  // By hand: M·(1, −2, 0.5, 0) = (2 − 1, −2 − 0.125, 0.125 + 2) = (1, −2.125, 2.125).
  EXPECT_TRUE(same(transform_direction(m, d), {1, -2.125, 2.125}));
}

TEST(SeedExamples, RotationRotatesDirectionsLikePoints) {
  // A quarter turn about z: (1, 0, 0) → (0, 1, 0), for points and directions alike (up to the rounding of
  // cos(π/2) ≈ 6e-17).
  const Transform r = Transform::rotation({0, 0, 1}, std::acos(-1.0) / 2);
  const Vec3 p = transform_point(r, {1, 0, 0}), d = transform_direction(r, {1, 0, 0});
  EXPECT_NEAR(p.x, 0, 1e-16);
  EXPECT_EQ(p.y, 1);
  EXPECT_TRUE(same(p, d));
}

// ---- Rays for pixels (§1.3) ------------------------------------------------------------------------------

TEST(Rays, NdcPixelCentres) {
  // m × n = 4 × 2: x = 2(i + ½)/4 − 1 ∈ {−0.75, −0.25, 0.25, 0.75}, y = 2(j + ½)/2 − 1 ∈ {−0.5, 0.5}, z = −1.
  const ImageSize image{4, 2};
  const double xs[4] = {-0.75, -0.25, 0.25, 0.75}, ys[2] = {-0.5, 0.5};
  for (std::uint32_t i = 0; i < 4; ++i)
    for (std::uint32_t j = 0; j < 2; ++j) {
      const Ray r = ndc_ray(i, j, image);
      EXPECT_TRUE(same(r.origin, {xs[i], ys[j], -1})) << i << "," << j << ": " << show(r.origin);
      EXPECT_TRUE(same(r.direction, {0, 0, 1}));
    }
  // A sample at the pixel's lower-left corner: x = 2·0/4 − 1 = −1.
  EXPECT_TRUE(same(ndc_ray(0, 0, image, {0, 0}).origin, {-1, -1, -1}));
  EXPECT_THROW((void)ndc_ray(4, 0, image), invalid_input);
  EXPECT_THROW((void)ndc_ray(0, 0, {0, 2}), invalid_input);
}

TEST(Rays, PerspectiveThroughTheNearPlaneWindow) {
  // A 1 × 1 image whose pixel centre is the window point (3, 4, −12): window [2, 4] × [3, 5] at near 12.
  // ‖o‖ = 13, so d = (3/13, 4/13, −12/13) (each within an ulp or two: one sqrt and a few roundings).
  const NearPlaneWindow w{2, 4, 3, 5, 12};
  const Ray r = perspective_ray(w, 0, 0, {1, 1});
  EXPECT_TRUE(same(r.origin, {3, 4, -12}));
  EXPECT_LE(ulps_apart(r.direction.x, 3.0 / 13), 2);
  EXPECT_LE(ulps_apart(r.direction.y, 4.0 / 13), 2);
  EXPECT_LE(ulps_apart(r.direction.z, -12.0 / 13), 2);
  const Ray from_eye = perspective_ray(w, 0, 0, {1, 1}, {}, RayStart::eye);
  EXPECT_TRUE(same(from_eye.origin, {0, 0, 0}));
  EXPECT_TRUE(same(from_eye.direction, r.direction));
  // Seed window with m × n = 4 × 2 over [−2, 2] × [−1, 1] at near 1: pixel (0, 0) is at
  // (−2 + 0.5/4·4, −1 + 0.5/2·2, −1) = (−1.5, −0.5, −1).
  EXPECT_TRUE(same(perspective_ray({-2, 2, -1, 1, 1}, 0, 0, {4, 2}).origin, {-1.5, -0.5, -1}));
  EXPECT_THROW((void)perspective_ray({-2, 2, -1, 1, 0}, 0, 0, {4, 2}), invalid_input);   // near = 0
  EXPECT_THROW((void)perspective_ray({2, 2, -1, 1, 1}, 0, 0, {4, 2}), invalid_input);    // empty window
}

TEST(Rays, Orthographic) {
  // Same window as above: origin on the window, direction (0, 0, −1) for every pixel.
  const Ray r = orthographic_ray({-2, 2, -1, 1, 1}, 3, 1, {4, 2});
  EXPECT_TRUE(same(r.origin, {1.5, 0.5, -1}));
  EXPECT_TRUE(same(r.direction, {0, 0, -1}));
}

TEST(Rays, FieldOfView) {
  // 90° vertical: top = near·tan 45° = near (up to one rounding of tan); aspect 2 doubles the width.
  const NearPlaneWindow w = window_from_field_of_view(90, 2, 0.5);
  EXPECT_NEAR(w.top, 0.5, 1e-16);
  EXPECT_EQ(w.bottom, -w.top);
  EXPECT_EQ(w.right, 2 * w.top);
  EXPECT_EQ(w.left, -w.right);
  EXPECT_EQ(w.near, 0.5);
  EXPECT_THROW((void)window_from_field_of_view(180, 1, 1), invalid_input);
  EXPECT_THROW((void)window_from_field_of_view(60, 0, 1), invalid_input);
}

TEST(Rays, NdcRaysThroughTheInversePerspectiveAreCameraRays) {
  // The notes' recommended route (docs/ray-casting.md §1.3): NDC ray → inverse perspective projection (two points and their
  // difference) → camera space. The result starts on the near-plane window at the pixel's point and
  // points away from the eye along it.
  const double l = -2, r = 2, b = -1, t = 1, n = 1, f = 100;
  const Transform to_camera = inverse(perspective_projection(l, r, b, t, n, f));
  EXPECT_FALSE(to_camera.is_affine());
  const ImageSize image{8, 4};
  for (std::uint32_t i = 0; i < image.width; ++i)
    for (std::uint32_t j = 0; j < image.height; ++j) {
      const Ray camera = transform_ray(to_camera, ndc_ray(i, j, image), Renormalize::yes);
      const Ray expected = perspective_ray({l, r, b, t, n}, i, j, image);
      EXPECT_NEAR(camera.origin.x, expected.origin.x, 1e-14);
      EXPECT_NEAR(camera.origin.y, expected.origin.y, 1e-14);
      EXPECT_NEAR(camera.origin.z, expected.origin.z, 1e-14);
      EXPECT_NEAR(camera.direction.x, expected.direction.x, 1e-13);
      EXPECT_NEAR(camera.direction.y, expected.direction.y, 1e-13);
      EXPECT_NEAR(camera.direction.z, expected.direction.z, 1e-13);
    }
}

TEST(Rays, PerspectiveProjectionByHand) {
  // glFrustum(−1, 1, −1, 1, 1, 3): rows (1 0 0 0), (0 1 0 0), (0 0 −2 −3), (0 0 −1 0). The near point
  // (0, 0, −1) goes to NDC z = −1, the far point (0, 0, −3) to z = +1.
  const Transform p = perspective_projection(-1, 1, -1, 1, 1, 3);
  const Transform expected{{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, -2, -3}, {0, 0, -1, 0}}}};
  EXPECT_EQ(p, expected);
  EXPECT_TRUE(same(transform_point(p, {0, 0, -1}), {0, 0, -1}));
  EXPECT_TRUE(same(transform_point(p, {0, 0, -3}), {0, 0, 1}));
  EXPECT_TRUE(same(transform_point(p, {0.5, -1, -2}), {0.25, -0.5, 0.5}));  // w = 2: (0.5, −1, 1)/2
  EXPECT_THROW((void)perspective_projection(-1, 1, -1, 1, 0, 3), invalid_input);
}

// ---- What is refused -------------------------------------------------------------------------------------

TEST(Refusals, ADirectionThroughAPerspectiveTransform) {
  const Transform p = perspective_projection(-1, 1, -1, 1, 1, 3);
  try {
    (void)transform_direction(p, {1, 0, 0});
    FAIL() << "no exception";
  } catch (const invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("perspective"), std::string::npos) << e.what();
  }
  // A ray is fine: two points.
  EXPECT_NO_THROW((void)transform_ray(p, {{0, 0, -1}, {0, 0, -1}}));
}

TEST(Refusals, PointsAtInfinityAndRaysCrossingWZero) {
  const Transform p = perspective_projection(-1, 1, -1, 1, 1, 3);
  EXPECT_THROW((void)transform_point(p, {0, 0, 0}), invalid_input);  // the eye: w = 0
  // From z = −1 (w = 1) towards +z by 2: o + d at z = 1 has w = −1: the segment crosses w = 0.
  EXPECT_THROW((void)transform_ray(p, {{0, 0, -1}, {0, 0, 2}}), invalid_input);
  EXPECT_THROW((void)transform_ray(Transform::identity(), {{0, 0, 0}, {0, 0, 0}}), invalid_input);
  EXPECT_THROW((void)transform_ray(Transform::scaling({1, 0, 1}), {{0, 0, 0}, {0, 1, 0}}), invalid_input);
}

TEST(Refusals, SingularInverse) {
  EXPECT_THROW((void)inverse(Transform::scaling({1, 0, 1})), invalid_input);
  EXPECT_EQ(inverse(Transform::translation({2, 3, 4})), Transform::translation({-2, -3, -4}));
  EXPECT_EQ(inverse(Transform::scaling({2, 4, 0.5})), Transform::scaling({0.5, 0.25, 2}));
}

TEST(Refusals, DegenerateCameras) {
  EXPECT_THROW((void)camera_to_world({1, 2, 3}, {1, 2, 3}, {0, 1, 0}), invalid_input);
  EXPECT_THROW((void)camera_to_world({0, 5, 0}, {0, 0, 0}, {0, 1, 0}), invalid_input);  // up ∥ view
  EXPECT_THROW((void)camera_to_world({0, 0, 5}, {0, 0, 0}, {0, 0, 0}), invalid_input);
  EXPECT_THROW((void)normalized({0, 0, 0}), invalid_input);
}

// ---- Cameras -----------------------------------------------------------------------------------------------

TEST(Cameras, CameraToWorldFromEyeTargetUp) {
  // Eye (0, 0, 5) looking at the origin, y up: the camera frame is the world frame moved to the eye.
  const Transform c = camera_to_world({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
  EXPECT_EQ(c, Transform::translation({0, 0, 5}));
  // Looking down −x from (10, 0, 0): camera −z is world −x, camera x (right) is world −z... u = up × w with
  // w = (1, 0, 0): u = (0, 1, 0) × (1, 0, 0) = (0, 0, −1); v = w × u = (0, 1, 0).
  const Transform side = camera_to_world({10, 0, 0}, {0, 0, 0}, {0, 1, 0});
  EXPECT_TRUE(same(transform_direction(side, {0, 0, -1}), {-1, 0, 0}));
  EXPECT_TRUE(same(transform_direction(side, {1, 0, 0}), {0, 0, -1}));
  EXPECT_TRUE(same(transform_point(side, {0, 0, 0}), {10, 0, 0}));
  // The world ray of the centre pixel of a 1 × 1 image goes from the eye's window point towards the target.
  const Camera camera = Camera::perspective(side, {-1, 1, -1, 1, 1}, {1, 1});
  const Ray r = camera.ray(0, 0);
  EXPECT_TRUE(same(r.origin, {9, 0, 0}));
  EXPECT_TRUE(same(r.direction, {-1, 0, 0}));
}

TEST(Cameras, StratifiedSamplesAreNRooksAndReproducible) {
  EXPECT_EQ(stratified_samples(1, 7, 3, 4).size(), 1u);
  EXPECT_EQ(stratified_samples(1, 7, 3, 4)[0].x, 0.5);
  for (std::uint32_t count : {2u, 3u, 4u, 9u, 16u, 33u}) {
    const std::vector<PixelSample> s = stratified_samples(count, 42, 10, 20);
    ASSERT_EQ(s.size(), count);
    std::set<std::uint32_t> columns, rows;
    for (const PixelSample& p : s) {
      ASSERT_GE(p.x, 0);
      ASSERT_LT(p.x, 1);
      ASSERT_GE(p.y, 0);
      ASSERT_LT(p.y, 1);
      columns.insert(static_cast<std::uint32_t>(p.x * count));
      rows.insert(static_cast<std::uint32_t>(p.y * count));
    }
    EXPECT_EQ(columns.size(), count) << "one sample per column stratum";
    EXPECT_EQ(rows.size(), count) << "one sample per row stratum";
    const std::vector<PixelSample> again = stratified_samples(count, 42, 10, 20);
    const std::vector<PixelSample> other_pixel = stratified_samples(count, 42, 11, 20);
    const std::vector<PixelSample> other_seed = stratified_samples(count, 43, 10, 20);
    for (std::size_t k = 0; k < count; ++k) {
      EXPECT_EQ(s[k].x, again[k].x);
      EXPECT_EQ(s[k].y, again[k].y);
    }
    EXPECT_NE(s[0].x, other_pixel[0].x);
    EXPECT_NE(s[0].x, other_seed[0].x);
  }
  EXPECT_THROW((void)stratified_samples(0, 1, 0, 0), invalid_input);
}

// ---- Properties against exact rational evaluation of the same formulas ------------------------------------

// A double in [lo, hi) with full 53-bit precision.
double uniform(double lo, double hi) {
  const auto bits = *rc::gen::inRange<std::uint64_t>(0, std::uint64_t{1} << 53);
  return lo + (hi - lo) * static_cast<double>(bits) * 0x1p-53;
}

RC_GTEST_PROP(Formulas, NdcOriginIsWithinThreeRoundingsOfExact, ()) {
  // x = 2(i + s)/m − 1 in three roundings (the ×2 is exact): |x̂ − x| ≤ γ_3·(|2(i + s)/m| + 1).
  const auto m = *rc::gen::inRange<std::uint32_t>(1, 100000);
  const auto i = *rc::gen::inRange<std::uint32_t>(0, m);
  const double s = uniform(0, 1);
  const Vector3<double> got = formulas::ndc_ray_origin<double>(i, i, m, m, s, s);
  const Vector3<mpq_class> exact = formulas::ndc_ray_origin<mpq_class>(i, i, m, m, mpq_class(s), mpq_class(s));
  const mpq_class q = 2 * (mpq_class(i) + mpq_class(s)) / m;
  RC_ASSERT(abs(mpq_class(got[0]) - exact[0]) <= gamma(3) * (q + 1));
  RC_ASSERT(got[2] == -1);
}

RC_GTEST_PROP(Formulas, NdcOriginIsExactForPowerOfTwoSizes, ()) {
  // m = 2^k and a sample with few bits: every operation is exact, so double == rational.
  const int k = *rc::gen::inRange(0, 20);
  const auto m = std::uint32_t{1} << k;
  const auto i = *rc::gen::inRange<std::uint32_t>(0, m);
  const double s = std::ldexp(*rc::gen::inRange(0, 1024), -10);
  const Vector3<double> got = formulas::ndc_ray_origin<double>(i, i, m, m, s, s);
  const Vector3<mpq_class> exact = formulas::ndc_ray_origin<mpq_class>(i, i, m, m, mpq_class(s), mpq_class(s));
  RC_ASSERT(mpq_class(got[0]) == exact[0]);
}

RC_GTEST_PROP(Formulas, NearPlanePointIsWithinFourRoundingsOfExact, ()) {
  // x = l + ((i + s)/m)·(r − l): |x̂ − x| ≤ γ_4·(|l| + |(i + s)/m·(r − l)|).
  const double l = uniform(-8, 8), r = uniform(-8, 8), near = uniform(0.01, 4);
  const auto m = *rc::gen::inRange<std::uint32_t>(1, 100000);
  const auto i = *rc::gen::inRange<std::uint32_t>(0, m);
  const double s = uniform(0, 1);
  const Vector3<double> got = formulas::near_plane_point<double>(l, r, l, r, near, i, i, m, m, s, s);
  const Vector3<mpq_class> exact = formulas::near_plane_point<mpq_class>(
      mpq_class(l), mpq_class(r), mpq_class(l), mpq_class(r), mpq_class(near), i, i, m, m, mpq_class(s), mpq_class(s));
  const mpq_class scale = abs(mpq_class(l)) + abs((mpq_class(i) + mpq_class(s)) / m * (mpq_class(r) - mpq_class(l)));
  RC_ASSERT(abs(mpq_class(got[0]) - exact[0]) <= gamma(4) * scale);
  RC_ASSERT(mpq_class(got[2]) == exact[2]);
}

Transform random_affine() {
  Transform t = Transform::identity();
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 4; ++j) t.m[i][j] = uniform(-4, 4);
  return t;
}

RC_GTEST_PROP(Formulas, AffinePointsAndDirectionsAreWithinTheDotProductBound, ()) {
  // Each component is a 4-term dot product (3 for a direction, whose w = 0 makes the last term exactly 0):
  // |x̂ − x| ≤ γ_4·Σ|M_ij v_j| (γ_3 for directions); the divide by w = 1 is exact.
  const Transform t = random_affine();
  const Vec3 p{uniform(-100, 100), uniform(-100, 100), uniform(-100, 100)};
  const Vec3 got_point = transform_point(t, p), got_direction = transform_direction(t, p);
  const Matrix4<mpq_class> m = exact_matrix(t);
  const Vector3<mpq_class> v = exact_vector(p);
  const Vector3<mpq_class> exact_point = formulas::perspective_divide(formulas::homogeneous_point(m, v));
  const Vector3<mpq_class> exact_direction = formulas::transform_direction(m, v);
  const double got_p[3] = {got_point.x, got_point.y, got_point.z}, got_d[3] = {got_direction.x, got_direction.y, got_direction.z};
  for (std::size_t r = 0; r < 3; ++r) {
    const mpq_class magnitude = abs(m[r][0] * v[0]) + abs(m[r][1] * v[1]) + abs(m[r][2] * v[2]);
    RC_ASSERT(abs(mpq_class(got_p[r]) - exact_point[r]) <= gamma(4) * (magnitude + abs(m[r][3])));
    RC_ASSERT(abs(mpq_class(got_d[r]) - exact_direction[r]) <= gamma(3) * magnitude);
  }
}

RC_GTEST_PROP(Formulas, AffineRaysAreExactForDyadicTransforms, ()) {
  // Entries and coordinates with few bits: every product and sum is exact, so the double ray is the exact
  // image, and the direction equals the difference of the two transformed points (docs/ray-casting.md §1.4).
  auto dyadic = [] { return std::ldexp(*rc::gen::inRange(-64, 65), -3); };
  Transform t = Transform::identity();
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 4; ++j) t.m[i][j] = dyadic();
  const Vec3 o{dyadic(), dyadic(), dyadic()}, d{dyadic(), dyadic(), dyadic()};
  RC_PRE(d.x != 0 || d.y != 0 || d.z != 0);
  const Matrix4<mpq_class> m = exact_matrix(t);
  const Vector3<mpq_class> exact_d = formulas::transform_direction(m, exact_vector(d));
  RC_PRE(exact_d[0] != 0 || exact_d[1] != 0 || exact_d[2] != 0);
  const Ray r = transform_ray(t, {o, d});
  const Vector3<mpq_class> exact_o = formulas::perspective_divide(formulas::homogeneous_point(m, exact_vector(o)));
  RC_ASSERT(exact_vector(r.origin) == exact_o);
  RC_ASSERT(exact_vector(r.direction) == exact_d);
  const Vec3 end = transform_point(t, {o.x + d.x, o.y + d.y, o.z + d.z});
  RC_ASSERT(same(r.direction, {end.x - r.origin.x, end.y - r.origin.y, end.z - r.origin.z}));
}

RC_GTEST_PROP(Formulas, PerspectivePointsAreWithinTheDivideBound, ()) {
  // X̂ = X + ε_X with |ε_X| ≤ γ_4·S_X (a 4-term dot product, S_X = Σ|M_0j v_j|), likewise Ŵ; then
  // x̂ = RN(X̂/Ŵ) and |x̂ − X/W| ≤ u·|X̂/Ŵ| + (γ_4·S_X + |X/W|·γ_4·S_W)/|Ŵ|, with |Ŵ| ≥ |W| − γ_4·S_W.
  const Transform p = perspective_projection(uniform(-2, -0.5), uniform(0.5, 2), uniform(-2, -0.5), uniform(0.5, 2),
                                             uniform(0.1, 1), uniform(10, 1000));
  const Vec3 point{uniform(-5, 5), uniform(-5, 5), uniform(-100, -0.2)};
  const Vec3 got = transform_point(p, point);
  const Matrix4<mpq_class> m = exact_matrix(p);
  const Vector4<mpq_class> h = formulas::homogeneous_point(m, exact_vector(point));
  const mpq_class w_magnitude = abs(m[3][0] * mpq_class(point.x)) + abs(m[3][1] * mpq_class(point.y)) +
                                abs(m[3][2] * mpq_class(point.z)) + abs(m[3][3]);
  const mpq_class w_low = abs(h[3]) - gamma(4) * w_magnitude;
  RC_PRE(w_low > 0);
  const double got_c[3] = {got.x, got.y, got.z};
  const double v[3] = {point.x, point.y, point.z};
  for (std::size_t r = 0; r < 3; ++r) {
    mpq_class magnitude = abs(m[r][3]);
    for (std::size_t j = 0; j < 3; ++j) magnitude += abs(m[r][j] * mpq_class(v[j]));
    const mpq_class exact = h[r] / h[3];
    const mpq_class bound = u_exact * (abs(exact) + (gamma(4) * magnitude + abs(exact) * gamma(4) * w_magnitude) / w_low) +
                            (gamma(4) * magnitude + abs(exact) * gamma(4) * w_magnitude) / w_low;
    RC_ASSERT(abs(mpq_class(got_c[r]) - exact) <= bound);
  }
}

RC_GTEST_PROP(Formulas, InverseOfSmallIntegerMatricesIsCorrectlyRounded, ()) {
  // With entries in [−6, 6] every cofactor and the determinant are small integers, exact in doubles, so
  // each entry of the double inverse is one division: RN(adj_ij/det), the exact inverse rounded.
  Transform t;
  for (auto& row : t.m)
    for (double& x : row) x = *rc::gen::inRange(-6, 7);
  const formulas::Adjugate<mpq_class> exact = formulas::adjugate(exact_matrix(t));
  RC_PRE(exact.determinant != 0);
  const Transform inv = inverse(t);
  const Matrix4<mpq_class> exact_inverse = formulas::inverse_from_adjugate(exact);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) RC_ASSERT(inv.m[i][j] == test_support::round_by_integer_division(exact_inverse[i][j]));  // ±0 alike
  // And M·M⁻¹ = I exactly in rationals.
  const Matrix4<mpq_class> product = formulas::multiply(exact_matrix(t), exact_inverse);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) RC_ASSERT(product[i][j] == (i == j ? 1 : 0));
}

RC_GTEST_PROP(Formulas, CameraFramesAreOrthonormal, ()) {
  // u, v, w from eye, target, up: unit length and mutually orthogonal within a few roundings (checked
  // exactly on the doubles produced), w pointing from the target to the eye, and the eye on the frame.
  const Vec3 eye{uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
  const Vec3 target{uniform(-50, 50), uniform(-50, 50), uniform(-50, 50)};
  const Vec3 up{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
  Transform c;
  try {
    c = camera_to_world(eye, target, up);
  } catch (const invalid_input&) {
    RC_DISCARD("degenerate camera");
  }
  Vector3<mpq_class> axis[3];
  for (std::size_t k = 0; k < 3; ++k) axis[k] = {mpq_class(c.m[0][k]), mpq_class(c.m[1][k]), mpq_class(c.m[2][k])};
  auto dot = [](const Vector3<mpq_class>& a, const Vector3<mpq_class>& b) { return mpq_class(a[0] * b[0] + a[1] * b[1] + a[2] * b[2]); };
  const mpq_class tolerance = 16 * u_exact;
  for (std::size_t k = 0; k < 3; ++k) {
    RC_ASSERT(abs(dot(axis[k], axis[k]) - 1) <= tolerance);
    for (std::size_t l = k + 1; l < 3; ++l) RC_ASSERT(abs(dot(axis[k], axis[l])) <= tolerance);
  }
  const Vector3<mpq_class> back{mpq_class(eye.x) - mpq_class(target.x), mpq_class(eye.y) - mpq_class(target.y),
                                mpq_class(eye.z) - mpq_class(target.z)};
  RC_ASSERT(dot(axis[2], back) > 0);
  RC_ASSERT(same(transform_point(c, {0, 0, 0}), eye));
}

}  // namespace
}  // namespace raykernel
