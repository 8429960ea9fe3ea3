// The two checks every certified query starts with, inline so that they cost a few instructions:
// validity of the input (finite components, nonzero direction and normal) and the floating-point
// environment the error bounds assume.
#pragma once

#include <raykernel/raykernel.hpp>

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#else
#include <cfenv>
#endif

namespace raykernel::detail {

// True for every valid query (and only for valid ones): x − x is 0 for finite x and NaN for ±inf and NaN.
[[nodiscard]] inline bool plausibly_valid(const Ray& r, const Plane& p) noexcept {
  const Vec3 &o = r.origin, &d = r.direction, &pt = p.point, &n = p.normal;
  const double finite_probe = ((o.x - o.x) + (o.y - o.y) + (o.z - o.z)) + ((d.x - d.x) + (d.y - d.y) + (d.z - d.z)) +
                              ((pt.x - pt.x) + (pt.y - pt.y) + (pt.z - pt.z)) + ((n.x - n.x) + (n.y - n.y) + (n.z - n.z));
  const bool nonzero_direction = (d.x != 0) | (d.y != 0) | (d.z != 0);
  const bool nonzero_normal = (n.x != 0) | (n.y != 0) | (n.z != 0);
  return (finite_probe == 0) & nonzero_direction & nonzero_normal;
}

// Round to nearest, no flush-to-zero or denormals-are-zero, and every floating-point exception masked (the
// fast path computes branch-free, so a query it will not certify may divide by zero or form inf − inf on the
// way; with traps enabled that would raise SIGFPE instead of falling back).
[[nodiscard]] inline bool default_floating_point_environment() noexcept {
#if defined(__x86_64__) || defined(_M_X64)
  // MXCSR bits 6–15: DAZ (6), the six exception masks (7–12, all set = masked), rounding control (13–14,
  // 00 = to nearest), FTZ (15). The default is 0x1F80; bits 0–5 are sticky status flags, ignored.
  return (_mm_getcsr() & 0xFFC0u) == 0x1F80u;
#else
  return std::fegetround() == FE_TONEAREST;
#endif
}

}  // namespace raykernel::detail
