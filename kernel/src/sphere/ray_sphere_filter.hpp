// Stage 1 of the ray–sphere cascade: the signs of C = f·f − r² (the origin) and D = B² − A·C (the relation) in
// binary64 with semi-static error bounds (docs/contract.md §10; the formula: ray_sphere_formula.hpp). The roots
// are not computed here: the expansion stage rounds them.
//   Error bound: |Ĉ − C| ≤ E_C = (κ_C ⊗ P_C) ⊕ μ_C and |D̂ − D| ≤ E_D = (κ_D ⊗ ((X ⊗ X) ⊕ (Y ⊗ Z))) ⊕ μ_D,
//   X = m_B ⊕ θ, Y = Â ⊕ θ, Z = P_C ⊕ θ, as derived in core/error_bounds.hpp (the ray–sphere section).
//   Valid range: all finite inputs (subnormal included); uncertain (never wrong) when anything overflows (a
//   bound is then +inf or NaN and no comparison holds). A zero C or D is never certified.
//   Certified by: proofs/sphere/SphereFilter.v, `sphere_filter_c_sound` and `sphere_filter_d_sound` (from
//   `sphere_c_encloses` and `sphere_d_encloses`), in the model (RN on the reals) for every binary64 input.
#pragma once

#include "core/absolute_terms.hpp"
#include "core/dot3_filter.hpp"
#include "core/error_bounds.hpp"
#include "core/sign.hpp"

#include <raykernel/sphere.hpp>

#include <cmath>

namespace raykernel::detail {

struct SphereFilterSigns {
  Sign c, d;  // sign(C), sign(D), or uncertain
  double a, b, c_value, d_value;  // Â, B̂, Ĉ, D̂: the roots' candidates when D > 0 (never a decision)
  double c_bound, d_bound;        // E_C, E_D: the sign of Ĉ is certain when |Ĉ| > E_C, of D̂ when |D̂| > E_D
};

[[nodiscard]] inline Sign sphere_filter_sign(double value, double bound) noexcept {
  if (value > bound) return Sign::positive;
  if (value < -bound) return Sign::negative;
  return Sign::uncertain;
}

[[nodiscard]] [[gnu::always_inline]] inline SphereFilterSigns sphere_filter(const Ray& ray, const Sphere& sphere) noexcept {
  const double d[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const double f[3] = {ray.origin.x - sphere.center.x, ray.origin.y - sphere.center.y,
                       ray.origin.z - sphere.center.z};
  // A = d·d and f·f are sums of rounded squares, never negative: their magnitudes are their values, bit for bit
  // (proofs/sphere/SphereFilter.v, `square_magnitude_value`), read as such.
  const Dot3Rounded ra = dot3_rounded_square(d);  // A = d·d
  const Dot3Rounded rb = dot3_rounded(f, d);      // B = f·d
  const Dot3Rounded rs = dot3_rounded_square(f);  // f·f
  const double q = sphere.radius * sphere.radius;
  const double c = rs.value - q;
  const double pc = rs.magnitude + q;  // P_C ≥ |Ĉ|
  const double ec =
      plus_absolute(bounds::sphere_filter_c_relative * pc, absolute_constant(bounds::sphere_filter_c_absolute));
  const double a = ra.value, b = rb.value;
  const double dv = b * b - a * c;
  // E_D from the magnitudes alone (E_A, E_B, E_C are within 2κ of them: SphereFilter.v, `floor_covers`).
  const double x = rb.magnitude + bounds::sphere_filter_d_floor, y = a + bounds::sphere_filter_d_floor,
               z = pc + bounds::sphere_filter_d_floor;
  const double ed = plus_absolute(bounds::sphere_filter_d_relative * (x * x + y * z),
                                  absolute_constant(bounds::sphere_filter_d_absolute));
  return {sphere_filter_sign(c, ec), sphere_filter_sign(dv, ed), a, b, c, dv, ec, ed};
}

}  // namespace raykernel::detail
