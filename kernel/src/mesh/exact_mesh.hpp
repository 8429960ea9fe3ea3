// The exact signs the mesh queries fall back on (kernel/src/mesh/): GMP rationals from the doubles' bits. This
// header exposes no GMP type; exact_mesh.cpp is the only translation unit that sees them. No CGAL.
#pragma once

#include <raykernel/interval.hpp>
#include <raykernel/raykernel.hpp>

namespace raykernel::detail::exact {

// The sign of (p_i − r_i)(q_j − r_j) − (p_j − r_j)(q_i − r_i) (Shewchuk's orient2d(p, q, r) in the plane of axes
// i and j), exactly.
[[nodiscard]] int orient2d_sign(const Vec3& p, const Vec3& q, const Vec3& r, int i, int j);

// The sign of det(a − o, b − o, c − o) = (a − o)·((b − o) × (c − o)), exactly: for a ray from o, the sign of
// docs/contract.md §6's num.
[[nodiscard]] int det3_sign(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& c);

// Whether p lies on the closed triangle (a, b, c), exactly: coplanar and, in a projection along an axis k with
// N_k ≠ 0, inside or on the boundary; for a degenerate triangle (N = 0), on one of its three edges.
[[nodiscard]] bool point_on_triangle(const Vec3& p, const Triangle& triangle);

// The sign of t1 − t2 for the exact t = num/den of docs/contract.md §6 of `ray` against two triangles whose den are
// nonzero: t = ((a − o)·N)/(d·N), N = (b − a) × (c − a). For nearest_hit(ray, mesh) when the rounded t tie.
[[nodiscard]] int compare_triangle_t(const Ray& ray, const Triangle& first, const Triangle& second);

// The exact value of a finite double as a rational in lowest terms (from its bits).
[[nodiscard]] Rational rational_of_double(double x);

// Whether the exact rational t lies in the valid interval [t_min, t_max] (docs/contract.md §8), the bounds taken
// as the rationals of their bits (t_max = +inf: no upper test). For the references.
[[nodiscard]] bool rational_in_interval(const Rational& t, const RayInterval& interval);

// The sign of x − y for two exact rationals (lowest terms or not, denominators nonzero).
[[nodiscard]] int compare_rationals(const Rational& x, const Rational& y);

}  // namespace raykernel::detail::exact
