// A probe of how the kernel's translation units evaluate floating-point expressions, for the test that
// detects a build contracting a·b − c into an FMA (tests/fp_environment_test.cpp).
#pragma once

namespace raykernel::detail {

// a·a − c, compiled with the kernel's flags (defined in api.cpp).
double contraction_probe(double a, double c) noexcept;

}  // namespace raykernel::detail
