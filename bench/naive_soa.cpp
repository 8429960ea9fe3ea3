// The seed's ray–plane formula over structure-of-arrays, as a plain loop the compiler vectorizes: the fair
// baseline for the SIMD batch (intersect/naive_soa/random_l2). Cloned for AVX-512, AVX2 and generic
// x86-64, chosen when the program loads, like the batch loops. Compiled with the kernel's floating-point
// flags (no contraction), so that it computes what intersect_naive computes.
#include "workloads.hpp"

#include <limits>

namespace raykernel::bench {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#endif
void naive_soa(const SoA& soa, Relation* relation, double* t) noexcept {
  const std::size_t n = soa.ox.size();
  const double *ox = soa.ox.data(), *oy = soa.oy.data(), *oz = soa.oz.data();
  const double *dx = soa.dx.data(), *dy = soa.dy.data(), *dz = soa.dz.data();
  const double *px = soa.px.data(), *py = soa.py.data(), *pz = soa.pz.data();
  const double *nx = soa.nx.data(), *ny = soa.ny.data(), *nz = soa.nz.data();
  for (std::size_t i = 0; i < n; ++i) {
    const double den = (dx[i] * nx[i] + dy[i] * ny[i]) + dz[i] * nz[i];
    const double num = ((px[i] - ox[i]) * nx[i] + (py[i] - oy[i]) * ny[i]) + (pz[i] - oz[i]) * nz[i];
    const double q = num / den;
    // parallel and in-plane (den = 0) are told apart as intersect_naive does; the loop stays branch-free
    const Relation r = den == 0 ? (num == 0 ? Relation::in_plane : Relation::parallel)
                                : (q >= 0 ? Relation::hit : Relation::behind);
    relation[i] = r;
    t[i] = den == 0 ? std::numeric_limits<double>::quiet_NaN() : q;
  }
}

}  // namespace raykernel::bench
