// The rounding of a root U ± √V of the exact ray–sphere stage (U, V rationals, V ≥ 0) to a binary format in a
// given mode: one correct rounding (exact_sphere.cpp). Written once, for the roots (to nearest, binary64) and for
// the thresholds of the sphere's spawn (directed, binary64 or binary32; sphere_spawn.cpp). Internal: GMP types.
#pragma once

#include "core/binary64_rounding.hpp"

#include <gmpxx.h>
#include <mpfr.h>

namespace raykernel::detail::exact {

// U + root·√V (root = ±1, V ≥ 0) rounded once to `format` in `mode`; `exact`, when given, says whether the
// rounded value is the root itself (only when √V is rational).
[[nodiscard]] double round_root(const mpq_class& u, const mpq_class& v, int root, const BinaryFormat& format,
                                mpfr_rnd_t mode, bool* exact = nullptr);

}  // namespace raykernel::detail::exact
