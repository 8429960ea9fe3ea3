// The ways renderers start a secondary ray at a hit point today, each written as its source publishes it (file
// and line in offset_methods.cpp), for `raykernel spawn-audit` and the spawn benchmarks: given the same hit,
// each gives the origin of the new ray and the start of its interval. Not certified; they are what raykernel's
// `spawn` is measured against.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/triangle.hpp>

#include <array>
#include <cstdint>
#include <string_view>

namespace raykernel::baseline {

// The hit as a renderer has it. The float methods get float values: the audit's meshes and directions are
// binary32 values (held in doubles), and `p32` is the exact hit point rounded to float.
struct OffsetHit {
  Vec3 p64;                           // the exact hit point P rounded to nearest in binary64
  Vec3 p32;                           // P rounded to nearest in binary32
  Triangle triangle;                  // the triangle hit (binary32 values)
  std::array<double, 3> barycentric;  // P's barycentric coordinates (RN in binary64)
  Vec3 primary_origin;                // the ray that found the hit, and its t (RN in binary64)
  double primary_t;
  Vec3 direction;                     // the new ray's direction (binary32 values)
};

// The new ray: its origin (values of the method's format) and where its interval starts (t > t_min, or
// t ≥ t_min when `t_min_included`), as the renderer's intersector treats it.
struct OffsetRay {
  Vec3 origin;
  double t_min;
  bool t_min_included;
};

enum class OffsetMethod : std::uint8_t { pbrt_v4, ray_tracing_gems, mitsuba3, embree_tutorial, one_weekend };
inline constexpr std::array<OffsetMethod, 5> offset_methods = {
    OffsetMethod::pbrt_v4, OffsetMethod::ray_tracing_gems, OffsetMethod::mitsuba3, OffsetMethod::embree_tutorial,
    OffsetMethod::one_weekend};

[[nodiscard]] OffsetRay offset_ray(OffsetMethod method, const OffsetHit& hit);
[[nodiscard]] std::string_view name(OffsetMethod method) noexcept;   // "pbrt-v4", ...
[[nodiscard]] bool is_binary32(OffsetMethod method) noexcept;        // all but Ray Tracing in One Weekend

}  // namespace raykernel::baseline
