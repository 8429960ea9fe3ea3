// raykernel: exact ray casting for binary64 inputs — every primitive, every query.
//
// The umbrella header: <raykernel/core.hpp> (rays, stages, exact rationals, invalid input), the primitives
// <raykernel/plane.hpp> (docs/contract.md §1), <raykernel/triangle.hpp> (§6) and <raykernel/sphere.hpp> (§10). Meshes, nearest hits,
// batches, cameras and threads have headers of their own (README, "The library").
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/plane.hpp>
#include <raykernel/triangle.hpp>
#include <raykernel/sphere.hpp>
