// The published offset methods, transcribed operation by operation in their own precision (float: binary32
// operations, FMA where the source calls one; compiled with -ffp-contract=off, so no other operation is fused).
// Each cites the file and line of its source, at the commit named.
#include "offset_methods.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace raykernel::baseline {
namespace {

struct F3 {
  float x, y, z;
};
F3 to_float(const Vec3& v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
Vec3 to_double(const F3& v) { return {v.x, v.y, v.z}; }
F3 operator-(const F3& a, const F3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
float dot(const F3& a, const F3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
F3 cross(const F3& a, const F3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
F3 normalize(const F3& v) {
  const float length = std::sqrt(dot(v, v));
  return {v.x / length, v.y / length, v.z / length};
}

// ---- pbrt-v4 (github.com/mmp/pbrt-v4, commit 5f7a6068) ------------------------------------------------------
// src/pbrt/util/math.h: DifferenceOfProducts and SumOfProducts (FMA-based, as pbrt's Cross and Dot use them).
float difference_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float difference = std::fma(a, b, -cd);
  const float error = std::fma(-c, d, cd);
  return difference + error;
}
float sum_of_products(float a, float b, float c, float d) {
  const float cd = c * d;
  const float sum = std::fma(a, b, cd);
  const float error = std::fma(c, d, -cd);
  return sum + error;
}
// src/pbrt/util/vecmath.h:999-1004: Cross (DifferenceOfProducts per component); :1057-1068: the Dot of a normal
// and a vector, FMA(n.x, v.x, SumOfProducts(n.y, v.y, n.z, v.z)).
F3 pbrt_cross(const F3& v, const F3& w) {
  return {difference_of_products(v.y, w.z, v.z, w.y), difference_of_products(v.z, w.x, v.x, w.z),
          difference_of_products(v.x, w.y, v.y, w.x)};
}
float pbrt_dot(const F3& v, const F3& w) { return std::fma(v.x, w.x, sum_of_products(v.y, w.y, v.z, w.z)); }
// Normalize(v) = v / Length(v), Length = sqrt(Sqr(x) + Sqr(y) + Sqr(z)) (vecmath.h:948-961).
F3 pbrt_normalize(const F3& v) {
  const float length = std::sqrt(dot(v, v));
  return {v.x / length, v.y / length, v.z / length};
}
// src/pbrt/util/float.h:195: gamma(n) = (n·MachineEpsilon)/(1 − n·MachineEpsilon), MachineEpsilon = FLT_EPSILON/2.
float gamma(int n) {
  const float machine_epsilon = std::numeric_limits<float>::epsilon() * 0.5f;
  return (static_cast<float>(n) * machine_epsilon) / (1 - static_cast<float>(n) * machine_epsilon);
}
// src/pbrt/util/float.h: NextFloatUp / NextFloatDown (the next float towards ±inf; −0 is treated as +0).
float next_float_up(float v) { return std::nextafter(v == 0 ? 0.0f : v, std::numeric_limits<float>::infinity()); }
float next_float_down(float v) { return std::nextafter(v == 0 ? -0.0f : v, -std::numeric_limits<float>::infinity()); }

OffsetRay pbrt_v4(const OffsetHit& h) {
  const F3 p0 = to_float(h.triangle.a), p1 = to_float(h.triangle.b), p2 = to_float(h.triangle.c);
  const float b0 = static_cast<float>(h.barycentric[0]), b1 = static_cast<float>(h.barycentric[1]),
              b2 = static_cast<float>(h.barycentric[2]);
  // src/pbrt/shapes.h:928-929: pAbsSum = Abs(b0 * p0) + Abs(b1 * p1) + Abs(b2 * p2); pError = gamma(7) * pAbsSum.
  const auto abs_scaled = [](float b, const F3& p) { return F3{std::fabs(b * p.x), std::fabs(b * p.y), std::fabs(b * p.z)}; };
  const F3 s0 = abs_scaled(b0, p0), s1 = abs_scaled(b1, p1), s2 = abs_scaled(b2, p2);
  const F3 sum{(s0.x + s1.x) + s2.x, (s0.y + s1.y) + s2.y, (s0.z + s1.z) + s2.z};
  const float g = gamma(7);
  const F3 error{g * sum.x, g * sum.y, g * sum.z};
  // src/pbrt/shapes.h:936: n = Normalize(Cross(dp02, dp12)), dp02 = p0 − p2, dp12 = p1 − p2.
  const F3 n = pbrt_normalize(pbrt_cross(p0 - p2, p1 - p2));
  // src/pbrt/ray.h:75-91, OffsetRayOrigin(pi, n, w).
  const float d = pbrt_dot({std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)}, error);
  F3 offset{d * n.x, d * n.y, d * n.z};
  if (pbrt_dot(to_float(h.direction), n) < 0) offset = {-offset.x, -offset.y, -offset.z};
  const F3 pi = to_float(h.p32);
  float po[3] = {pi.x + offset.x, pi.y + offset.y, pi.z + offset.z};
  const float off[3] = {offset.x, offset.y, offset.z};
  for (int i = 0; i < 3; ++i) {
    if (off[i] > 0)
      po[i] = next_float_up(po[i]);
    else if (off[i] < 0)
      po[i] = next_float_down(po[i]);
  }
  // pbrt's triangle test accepts 0 < t (src/pbrt/shapes.h, IntersectTriangle: t_scaled <= 0 is a miss).
  return {to_double({po[0], po[1], po[2]}), 0, false};
}

// ---- Ray Tracing Gems ch. 6, as Cycles ships it (github.com/blender/cycles, commit d19c1a45) ---------------
// src/kernel/bvh/util.h:68-83, ray_offset(P, Ng): the normal's components scaled by int_scale = 256 become
// integer offsets of the float's bits (away from zero), except within origin = 1/32 of zero, where
// float_scale·Ng (1/65536) is added. Cycles calls it with the geometric normal turned to the side the new ray
// leaves towards; Ng there is normalize(cross(v1 − v0, v2 − v0)) (src/kernel/geom/triangle.h).
float add_to_bits(float p, std::int32_t offset) {
  const auto bits = std::bit_cast<std::int32_t>(p);
  // __int_as_float(__float_as_int(P) + (P < 0 ? −of : of)), in two's complement.
  const auto sum = static_cast<std::uint32_t>(bits) + static_cast<std::uint32_t>(p < 0 ? -offset : offset);
  return std::bit_cast<float>(sum);
}
OffsetRay ray_tracing_gems(const OffsetHit& h) {
  const F3 v0 = to_float(h.triangle.a), v1 = to_float(h.triangle.b), v2 = to_float(h.triangle.c);
  F3 ng = normalize(cross(v1 - v0, v2 - v0));
  if (dot(to_float(h.direction), ng) < 0) ng = {-ng.x, -ng.y, -ng.z};
  const float int_scale = 256.0f;
  const std::int32_t of[3] = {static_cast<std::int32_t>(int_scale * ng.x), static_cast<std::int32_t>(int_scale * ng.y),
                              static_cast<std::int32_t>(int_scale * ng.z)};
  const F3 p = to_float(h.p32);
  const float pc[3] = {p.x, p.y, p.z}, nc[3] = {ng.x, ng.y, ng.z};
  const float origin = 1.0f / 32.0f;
  const float float_scale = 1.0f / 65536.0f;
  float r[3];
  for (int i = 0; i < 3; ++i) r[i] = std::fabs(pc[i]) < origin ? pc[i] + float_scale * nc[i] : add_to_bits(pc[i], of[i]);
  return {to_double({r[0], r[1], r[2]}), 0, false};
}

// ---- Mitsuba 3 (github.com/mitsuba-renderer/mitsuba3, commit b45b0a93) -------------------------------------
// include/mitsuba/render/interaction.h:186-190, Interaction::offset_p(d):
//   mag = (1 + max(|p|))·RayEpsilon; mag = mulsign(mag, dot(n, d)); return fmadd(mag, n, p);
// include/mitsuba/core/math.h:20: RayEpsilon = Epsilon·1500 (Epsilon of float: 2^-24). n is the triangle's
// geometric normal, normalize(cross(p1 − p0, p2 − p0)) (src/shapes/mesh.cpp).
OffsetRay mitsuba3(const OffsetHit& h) {
  const F3 p0 = to_float(h.triangle.a), p1 = to_float(h.triangle.b), p2 = to_float(h.triangle.c);
  const F3 n = normalize(cross(p1 - p0, p2 - p0));
  const F3 p = to_float(h.p32);
  const float ray_epsilon = 0x1p-24f * 1500;
  float mag = (1.f + std::fmax(std::fmax(std::fabs(p.x), std::fabs(p.y)), std::fabs(p.z))) * ray_epsilon;
  mag = std::copysign(mag, dot(n, to_float(h.direction)));
  return {to_double({std::fma(mag, n.x, p.x), std::fma(mag, n.y, p.y), std::fma(mag, n.z, p.z)}), 0, false};
}

// ---- Embree's path tracer tutorial (github.com/embree/embree, commit 0c236df6) ----------------------------
// tutorials/pathtracer/pathtracer_device.cpp:1119-1120: e = max(|p0|, |p1|, |p2|, |org|) (per component);
//   eps = 32·1.19209e-07·max(e.x, e.y, e.z, tfar);
// :1597-1599: sign = dot(wi, Ng) < 0 ? −1 : 1; P = P + sign·eps·Ng; the new ray's tnear = eps. Ng is Embree's
// geometric normal cross(v2 − v0, v0 − v1), normalized (face_forward only flips it; the sign undoes that).
// Embree counts hits with tnear ≤ t.
OffsetRay embree_tutorial(const OffsetHit& h) {
  const F3 p0 = to_float(h.triangle.a), p1 = to_float(h.triangle.b), p2 = to_float(h.triangle.c);
  const F3 org = to_float(h.primary_origin);
  const auto m = [](float a, float b, float c, float d) {
    return std::fmax(std::fmax(std::fabs(a), std::fabs(b)), std::fmax(std::fabs(c), std::fabs(d)));
  };
  const F3 e{m(p0.x, p1.x, p2.x, org.x), m(p0.y, p1.y, p2.y, org.y), m(p0.z, p1.z, p2.z, org.z)};
  const float tfar = static_cast<float>(h.primary_t);
  const float eps = 32.0f * 1.19209e-07f * std::fmax(std::fmax(e.x, e.y), std::fmax(e.z, tfar));
  const F3 ng = normalize(cross(p2 - p0, p0 - p1));
  const float sign = dot(to_float(h.direction), ng) < 0.0f ? -1.0f : 1.0f;
  const float scaled = sign * eps;
  const F3 p = to_float(h.p32);
  return {to_double({p.x + scaled * ng.x, p.y + scaled * ng.y, p.z + scaled * ng.z}), eps, true};
}

// ---- Ray Tracing in One Weekend (github.com/RayTracing/raytracing.github.io, v4) ------------------------------
// src/InOneWeekend/camera.h: ray_color traces the scattered ray from rec.p with interval(0.001, infinity), and
// interval::surrounds is min < t < max. rec.p is the hit point in double (here: the exact P rounded).
OffsetRay one_weekend(const OffsetHit& h) { return {h.p64, 0.001, false}; }

}  // namespace

OffsetRay offset_ray(OffsetMethod method, const OffsetHit& hit) {
  switch (method) {
    case OffsetMethod::pbrt_v4: return pbrt_v4(hit);
    case OffsetMethod::ray_tracing_gems: return ray_tracing_gems(hit);
    case OffsetMethod::mitsuba3: return mitsuba3(hit);
    case OffsetMethod::embree_tutorial: return embree_tutorial(hit);
    case OffsetMethod::one_weekend: return one_weekend(hit);
  }
  return one_weekend(hit);
}

std::string_view name(OffsetMethod method) noexcept {
  switch (method) {
    case OffsetMethod::pbrt_v4: return "pbrt-v4";
    case OffsetMethod::ray_tracing_gems: return "rtgems-cycles";
    case OffsetMethod::mitsuba3: return "mitsuba3";
    case OffsetMethod::embree_tutorial: return "embree-tutorial";
    case OffsetMethod::one_weekend: return "one-weekend";
  }
  return "?";
}

bool is_binary32(OffsetMethod method) noexcept { return method != OffsetMethod::one_weekend; }

}  // namespace raykernel::baseline
