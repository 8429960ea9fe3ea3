// The rounding of U ± √V (U, V rationals, V ≥ 0) to a binary format in a given mode: one correct rounding.
// Written once, for the roots of the exact ray–sphere stage (to nearest, binary64; sphere/exact_sphere.cpp), the
// thresholds of the sphere's spawn (directed, binary64 or binary32; sphere/sphere_spawn.cpp) and the distance of
// the closest point (U = 0; closest/closest_point.cpp). Internal: GMP types.
//
// √V is rational exactly when V's numerator and denominator, in lowest terms, are perfect squares; then U ± √V is
// rounded as a rational, ties included. Otherwise it is irrational, so neither a double nor a midpoint of two
// doubles: an enclosure [lo, hi] of it, computed by MPFR with directed roundings, whose two ends round to the
// same value gives the rounding of the root (every rounding is monotonic), and doubling the precision until they
// do terminates.
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
