// raykernel: exact ray casting for binary64 inputs — every primitive, every query.
//
// The umbrella header: <raykernel/core.hpp> (rays, stages, exact rationals, invalid input), the primitives
// <raykernel/plane.hpp> (docs/contract.md §1) and <raykernel/triangle.hpp> (§6). Meshes, nearest hits,
// batches, cameras and threads have headers of their own (README, "The library").
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <raykernel/core.hpp>
#include <raykernel/plane.hpp>
#include <raykernel/triangle.hpp>
