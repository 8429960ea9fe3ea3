// The exact stage of the nearest-hit predicates: signs of num and den, and the order of two t values, in
// exact rational arithmetic (GMP's mpq_class, without CGAL). Used as the last stage of nearest_hit and by
// nearest_hit_exact, the reference. This header exposes no GMP type.
#pragma once

#include <raykernel/raykernel.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace raykernel::detail::exact {

// The exact signs (−1, 0, +1) of num = (p − o)·n and den = d·n.
struct ExactSigns {
  int num;
  int den;
};
[[nodiscard]] ExactSigns ray_plane_signs(const Ray& ray, const Plane& plane);

// The exact sign of Δ = num_a·den_b − num_b·den_a (num and den of `a` and `b` along `ray`). With den_a,
// den_b ≠ 0, sign(t_a − t_b) = sign(Δ)·sign(den_a)·sign(den_b).
[[nodiscard]] int compare_quotients(const Ray& ray, const Plane& a, const Plane& b);

// The indices (ascending) of the planes that do not coincide with an earlier plane of the span: plane j
// coincides with plane i when both describe the same point set {x : n·x = n·p}, i.e. their normals are
// parallel and p_j lies on plane i, decided exactly. Two coincident planes have the same t along every
// ray. Each plane is reduced to a canonical exact key (normal and offset divided by the normal's first
// nonzero component), so the cost is O(k log k). Planes must be valid input.
[[nodiscard]] std::vector<std::uint32_t> distinct_planes(std::span<const Plane> planes);

// The index of the plane with the smallest exact t among those hit (num/den ≥ 0, den ≠ 0), ties to the
// smallest index; empty when no plane is hit. Planes and ray must be valid input.
[[nodiscard]] std::optional<std::size_t> nearest_plane(const Ray& ray, std::span<const Plane> planes);

}  // namespace raykernel::detail::exact
