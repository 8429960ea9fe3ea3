// The expansion stage of the ray–sphere query (docs/contract.md §10): A, B, C, D of ray_sphere_formula.hpp as
// exact floating-point expansions, and the side of a root against a rounding boundary m = (x + y)/2 from the
// exact signs of 4·q(m) = A·M² + 4B·M + 4C and 2·(A·m + B) = A·M + 2B with M = x + y = TwoSum(x, y).
//
//   f_i = TwoDiff(o_i, c_i) (2 components, exact), A = Σ d_i·d_i (6), B = Σ f_i·d_i (12), C = Σ f_i·f_i − r² (26),
//   D = B·B − C·A (600): exact products and sums of expansions, A, B and C compressed first (a few components
//   each, so that D's products are short).
//   Valid range: every TwoProduct of the products exact (|a·b| ≥ 2^-969 or a zero factor) and every component
//   finite — ExpansionBuilder::exact(); otherwise the exact stage decides.
//   Certified by: proofs/core/Expansions.v, `scale_gen_exact`, `sum_gen_exact` and `multiply_gen_exact` (each
//   expansion's exact sum is the polynomial's value when the builder stays exact) and `expansion_sign_sound` (a
//   certain sign is the sign of the exact sum); proofs/core/ExpansionCompress.v, `compress_gen_exact` (the
//   compression keeps the exact sum); the root's side: proofs/sphere/SphereRoots.v,
//   `root_side_of_smaller_correct` and `root_side_of_larger_correct`; the rounding from the sides:
//   proofs/core/MidpointRounding.v, `boundary_decision_correct`. The stage's composition (which polynomial each
//   expansion is), on twins that thread the builder's flag as the plane's and the triangle's do: a, b, c are A,
//   B, C after sphere_abc_expansions, and d is D after sphere_expansions, when the builder says exact:
//   proofs/sphere/SphereStages.v, `sphere_abc_expansions_exact` and `sphere_expansions_exact` (capacities:
//   `sphere_abc_expansions_length`, `sphere_expansions_length`); a certain sphere_root_side is sign(t_k − m):
//   proofs/sphere/SphereStages.v, `sphere_root_side_sound` and `sphere_root_side_expansions_sound`.
#pragma once

#include "core/eft.hpp"
#include "core/expansion.hpp"
#include "core/expansion_compare.hpp"
#include "core/sign.hpp"
#include "sphere/ray_sphere_formula.hpp"

#include <raykernel/sphere.hpp>

#include <cstddef>

namespace raykernel::detail {

struct SphereExpansions {
  ExpansionBuilder builder;
  Expansion<6> a;
  Expansion<12> b;
  Expansion<26> c;
  Expansion<600> d;
};

namespace sphere_internal {

template <std::size_t N>
void negate(Expansion<N>& e) noexcept {
  for (std::size_t i = 0; i < e.size; ++i) e.component[i] = -e.component[i];  // exact
}

inline Expansion<1> single(double x) noexcept {
  Expansion<1> e;
  e.component[0] = x;
  e.size = 1;
  return e;
}

template <std::size_t M, std::size_t N, std::size_t K, std::size_t L>
void sum3(const Expansion<M>& x, const Expansion<N>& y, const Expansion<K>& z, Expansion<L>& h) noexcept {
  Expansion<M + N> xy;
  ExpansionBuilder::sum(x, y, xy);
  ExpansionBuilder::sum(xy, z, h);
}

}  // namespace sphere_internal

// A, B, C as expansions (s.d left empty); `builder.exact()` says whether they are the exact values. The roots'
// rounding needs only these: the cascade builds D (below) only when the filter left the relation open.
inline void sphere_abc_expansions(const Ray& ray, const Sphere& sphere, SphereExpansions& s) noexcept {
  using namespace sphere_internal;
  ExpansionBuilder& builder = s.builder;
  const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
  const double dv[3] = {ray.direction.x, ray.direction.y, ray.direction.z};
  const double cv[3] = {sphere.center.x, sphere.center.y, sphere.center.z};
  Expansion<2> f[3], dd[3];
  Expansion<4> fd[3];
  Expansion<8> ff[3];
  for (int i = 0; i < 3; ++i) {
    ExpansionBuilder::from_pair(two_diff(o[i], cv[i]), f[i]);
    builder.check_finite(f[i]);
    ExpansionBuilder::from_pair(builder.product(dv[i], dv[i]), dd[i]);
    builder.scale(f[i], dv[i], fd[i]);
    multiply_expansions(builder, f[i], f[i], ff[i]);
  }
  Expansion<6> a;
  Expansion<12> b;
  Expansion<26> c;
  sum3(dd[0], dd[1], dd[2], a);
  sum3(fd[0], fd[1], fd[2], b);
  Expansion<24> f_squared;
  sum3(ff[0], ff[1], ff[2], f_squared);
  Expansion<2> r_squared;
  ExpansionBuilder::from_pair(builder.product(sphere.radius, sphere.radius), r_squared);
  negate(r_squared);
  ExpansionBuilder::sum(f_squared, r_squared, c);
  builder.check_finite(a);
  builder.check_finite(b);
  builder.check_finite(c);
  // Compressed (exact: every step a TwoSum of finite components), so that D's products and the roots' are short.
  ExpansionBuilder::compress(a, s.a);
  ExpansionBuilder::compress(b, s.b);
  ExpansionBuilder::compress(c, s.c);
  builder.check_finite(s.a);
  builder.check_finite(s.b);
  builder.check_finite(s.c);
}

// D = B·B − C·A from the expansions of sphere_abc_expansions, on the same builder.
inline void sphere_d_expansion(SphereExpansions& s) noexcept {
  using namespace sphere_internal;
  ExpansionBuilder& builder = s.builder;
  Expansion<288> b_squared;
  multiply_expansions(builder, s.b, s.b, b_squared);
  Expansion<312> a_c;
  multiply_expansions(builder, s.c, s.a, a_c);
  negate(a_c);
  ExpansionBuilder::sum(b_squared, a_c, s.d);
  builder.check_finite(b_squared);
  builder.check_finite(a_c);
  builder.check_finite(s.d);
}

// A, B, C, D as expansions; `builder.exact()` says whether they are the exact values.
inline void sphere_expansions(const Ray& ray, const Sphere& sphere, SphereExpansions& s) noexcept {
  sphere_abc_expansions(ray, sphere, s);
  sphere_d_expansion(s);
}

// sign(t_k − (x + y)/2) for the root k (−1: t1 or t0, +1: t2 or t0), D ≥ 0, from exact expansions A, B, C
// (uncertain when a product is not exact or a sign is not read).
inline Sign sphere_root_side(const SphereExpansions& s, int root, double x, double y) noexcept {
  using namespace sphere_internal;
  ExpansionBuilder builder;
  Expansion<2> m2;  // M = x + y, exactly
  ExpansionBuilder::from_pair(two_sum(x, y), m2);
  builder.check_finite(m2);
  Expansion<8> mm;
  multiply_expansions(builder, m2, m2, mm);
  Expansion<96> a_mm;
  multiply_expansions(builder, mm, s.a, a_mm);
  Expansion<48> b_m;
  multiply_expansions(builder, s.b, m2, b_m);
  Expansion<96> b_m4;
  builder.scale(b_m, 4.0, b_m4);
  Expansion<52> c4;
  builder.scale(s.c, 4.0, c4);
  Expansion<244> q4;
  sum3(a_mm, b_m4, c4, q4);
  Expansion<24> a_m;
  multiply_expansions(builder, s.a, m2, a_m);
  Expansion<24> b2;
  builder.scale(s.b, 2.0, b2);
  Expansion<48> slope2;
  ExpansionBuilder::sum(a_m, b2, slope2);
  builder.check_finite(q4);
  builder.check_finite(slope2);
  if (!builder.exact()) return Sign::uncertain;
  const Sign q = ExpansionBuilder::sign_or_compressed(q4), slope = ExpansionBuilder::sign_or_compressed(slope2);
  if (!is_certain(q) || !is_certain(slope)) return Sign::uncertain;
  return sign_from_int(root_side_of(root, static_cast<int>(q), static_cast<int>(slope)));
}

}  // namespace raykernel::detail
