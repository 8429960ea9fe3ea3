// raykernel/spawn.hpp: the origin of a secondary ray that provably never re-hits the surface it leaves
// (docs/contract.md §9).
//
// A renderer starts a reflected, refracted or shadow ray at a hit point P. P = o + t·d is exact as a rational
// but generally not representable, and its rounding may lie on either side of the surface, so the new ray can
// hit the surface it leaves ("self-intersection", "shadow acne"). spawn returns the representable origin
// nearest to P in the stated sense that is strictly on the side the new ray leaves towards:
//
//   s = sign(w·N) (spawn) or σ(q) (spawn_to), with N = (b − a) × (c − a) and σ(x) = sign((x − a)·N);
//   P̂ = P rounded to nearest-even in the origin's format F (binary64, or binary32 straight from the exact P);
//   if σ(P̂) = s the origin is P̂ and k = 0; otherwise coordinate i (the largest |N_i|, the smallest i on an
//   exact tie) of P̂ moves k steps through the finite values of F (one zero, as nextafter walks them) in the
//   direction sign(N_i)·s, for the smallest k ≥ 1 that gives σ = s.
//
// Guarantee: the origin is strictly on side s, so the ray from it along w meets the triangle's plane only at
// t < 0 — it never hits the source triangle under either rule; with spawn_to, the segment from the origin to q
// (§8) never meets it. k is exact (it can exceed 2^53 and 2^63; it is below 2^64).
//
// Invalid input (invalid_input, naming the reason): a non-finite component, a zero d or w, N = 0 (a degenerate
// triangle), den = d·N = 0 (the ray parallel to the plane), w·N = 0, σ(q) = 0, a P̂ that overflows F, or no
// value of F on side s along axis i.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/mesh.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/triangle.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace raykernel {

// The format of the origin: binary64, or binary32 for renderers that trace in float.
enum class OriginFormat : std::uint8_t { binary64, binary32 };

// Where the hit point P is: where the ray's line crosses the triangle's plane (P = o + (num/den)·d exactly,
// whatever the sign of t and whether or not inside the triangle), or a point of doubles (P = p; it need not lie
// on the plane).
struct HitPoint {
  enum class Kind : std::uint8_t { ray_crossing, point };
  Kind kind;
  Ray ray;      // ray_crossing
  Vec3 point;   // point
  [[nodiscard]] static HitPoint crossing(const Ray& r) noexcept { return {Kind::ray_crossing, r, {}}; }
  [[nodiscard]] static HitPoint at(const Vec3& p) noexcept { return {Kind::point, {}, p}; }
};

// The origin (each coordinate a value of the format: for binary32, a float held exactly in a double) and k,
// the steps it took from P̂.
struct SpawnedOrigin {
  Vec3 origin;
  std::uint64_t steps;
};

// The origin for a new ray along `direction` leaving the source triangle's plane towards sign(w·N).
[[nodiscard]] SpawnedOrigin spawn(const HitPoint& hit, const Triangle& source, const Vec3& direction,
                                  OriginFormat format = OriginFormat::binary64);

// The origin for a shadow ray towards the point `target` (s = σ(q)): the segment from it to q never meets the
// source triangle.
[[nodiscard]] SpawnedOrigin spawn_to(const HitPoint& hit, const Triangle& source, const Vec3& target,
                                     OriginFormat format = OriginFormat::binary64);

// spawn and spawn_to decided in exact rationals alone (GMP, MPFR): the reference spawn's certified fast path is
// tested against, and the path it hands every case to that it cannot certify. Same answers, same errors.
[[nodiscard]] SpawnedOrigin spawn_exact(const HitPoint& hit, const Triangle& source, const Vec3& direction,
                                        OriginFormat format = OriginFormat::binary64);
[[nodiscard]] SpawnedOrigin spawn_to_exact(const HitPoint& hit, const Triangle& source, const Vec3& target,
                                           OriginFormat format = OriginFormat::binary64);

// P̂: the hit point P rounded to nearest-even in the format, coordinate by coordinate (what spawn starts from).
// Invalid input as for spawn; a coordinate that overflows the format is ±inf.
[[nodiscard]] Vec3 rounded_hit_point(const HitPoint& hit, const Triangle& source,
                                     OriginFormat format = OriginFormat::binary64);

// σ(x) = sign((x − a)·N), N = (b − a) × (c − a): the side of the triangle's plane a point lies on (0: on it),
// exactly. Throws invalid_input for a non-finite value.
[[nodiscard]] int plane_side(const Vec3& point, const Triangle& triangle);
// sign(w·N): the side a direction leaves the plane towards (0: parallel to it), exactly.
[[nodiscard]] int direction_side(const Vec3& direction, const Triangle& triangle);

// ---- The exact ground truth of a secondary ray -----------------------------------------------------------
// What `raykernel spawn-audit` checks the offset methods renderers use against. A new ray starts at `from` —
// the exact hit point P where the ray crosses the plane of `source` (HitPoint::crossing; P is a rational point,
// generally not representable), or a point of doubles (HitPoint::at; `source` is then not used) — and goes
// along `direction`. A triangle counts when the ray meets it under the closed rule (docs/contract.md §6: any
// point of the closed triangle; coplanar and degenerate triangles never) at an exact t in the interval: t ≥ t_min
// (`t_min_included`), or t > t_min (t > 0: what the ray meets at its start point itself left out). Both are
// exact for every input (GMP rationals); invalid input (a non-finite value, a zero direction, t_min negative or
// not finite, a crossing parallel to the plane of `source`, an invalid mesh) throws invalid_input.
struct SecondaryInterval {
  double t_min = 0;
  bool t_min_included = true;
};

// Whether the ray meets `triangle` with t in the interval.
[[nodiscard]] bool hits_exact(const HitPoint& from, const Triangle& source, const Vec3& direction,
                              const Triangle& triangle, const SecondaryInterval& interval = {});

// The triangles of `mesh` (indices, ascending) that the ray meets first — at the least exact t in the interval —
// leaving out the triangle `skip`; empty when it meets none. Each triangle's box is tested first against the
// box of the start point swept along the direction, with slab bounds rounded outwards, which sets most aside
// without rationals; the rest are decided in rationals.
[[nodiscard]] std::vector<std::uint32_t> first_hits_exact(const HitPoint& from, const Triangle& source,
                                                          const Vec3& direction, const Mesh& mesh,
                                                          const SecondaryInterval& interval = {},
                                                          std::optional<std::uint32_t> skip = std::nullopt);

// ---- Spawning from a sphere (docs/contract.md, "Decided here": spawning from a sphere) -----------------------
// The sphere's rule, as the triangle's with the sphere's sides. P = p, the point of doubles the renderer holds
// (the exact hit o + t·d of a ray is irrational in general; p need not lie on the sphere); N = p − c, the
// outward normal there; s = sign(w·N), the side w leaves towards (+1 outward, −1 inward); σ(x) = sign(|x − c|² −
// r²). An origin x is accepted when it is strictly on side s — σ(x) = s — and, leaving outward, also
// w·(x − c) ≥ 0. P̂ = p rounded to nearest-even in F. If P̂ is accepted, k = 0; otherwise coordinate i of P̂ moves
// k steps through the finite values of F in direction δ = sign(N_i)·s, for the smallest k ≥ 1 that is accepted:
// i is the axis of the largest |N_i| (the smallest i on an exact tie), among the axes with w_i·N_i > 0 when
// leaving outward (there is one: w·N > 0), so that each step outward raises w·(x − c).
//
// Guarantee (proofs/sphere/SphereSpawn.v): leaving outward, the ray from the origin along w never meets the
// sphere (no root t ≥ 0: `spawn_outward_never_hits`); leaving inward, the origin is strictly inside, so the ray
// meets the sphere exactly once at t ≥ 0, where it leaves it (`spawn_inward_one_exit`). k is exact (< 2^64).
//
// Invalid input (invalid_input, naming the reason): a non-finite component, a radius not positive, a zero w,
// p = c (no normal), w·N = 0 (w tangent to the sphere at p), a P̂ that overflows F, or no accepted value of F
// along axis i (leaving inward: none strictly inside the sphere on that axis, or P̂ already past it).
[[nodiscard]] SpawnedOrigin spawn(const Vec3& point, const Sphere& source, const Vec3& direction,
                                  OriginFormat format = OriginFormat::binary64);

// σ(x) = sign(|x − c|² − r²): outside (+1), on the sphere (0) or inside (−1), exactly. Throws invalid_input for
// a non-finite value or a radius not positive.
[[nodiscard]] int sphere_side(const Vec3& point, const Sphere& sphere);

[[nodiscard]] std::string_view to_string(OriginFormat format) noexcept;  // "binary64", "binary32"

}  // namespace raykernel
