// "Your" ray code: what the examples test against raykernel. It is the ray–plane intersection found in many
// renderers — plain doubles and an epsilon for "parallel" — and a nearest-hit loop built on it. Both are
// wrong on hard inputs, which is what the examples find.
#pragma once

#include <raykernel/raykernel.hpp>

#include <span>

namespace my {

// t = ((p − o)·n) / (d·n) in doubles; |d·n| < 1e-12 counts as parallel (in-plane when also |(p − o)·n| <
// 1e-12).
raykernel::Intersection ray_plane(const raykernel::Ray& ray, const raykernel::Plane& plane);

// The index of the plane the ray hits first (smallest t ≥ 0, ties to the smaller index), or -1.
int nearest_hit(const raykernel::Ray& ray, std::span<const raykernel::Plane> planes);

}  // namespace my
