// Compile-time checks of the floating-point model that the certified stages and their proofs assume
// (proofs/README.md, "Assumptions"). Included by every translation unit with certified code.
#pragma once

#include <cfloat>
#include <limits>

static_assert(std::numeric_limits<double>::is_iec559, "raykernel needs IEEE-754 binary64 doubles");
static_assert(std::numeric_limits<double>::digits == 53, "raykernel needs binary64 (53-bit significands)");
static_assert(std::numeric_limits<double>::has_denorm == std::denorm_present,
              "raykernel needs gradual underflow (subnormal doubles)");
// FLT_EVAL_METHOD == 0: each double operation is evaluated in double, not in x87 80-bit registers that
// would round twice. (-mfpmath=387 makes it 2.)
static_assert(FLT_EVAL_METHOD == 0, "raykernel needs double operations evaluated in double (SSE2, not x87)");
#if defined(__FAST_MATH__)
#error "raykernel's certified code must not be compiled with -ffast-math"
#endif
#if defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__
#error "raykernel's certified code relies on inf and NaN propagation; do not use -ffinite-math-only"
#endif
