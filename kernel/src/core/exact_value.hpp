// The exact number type the formulas are instantiated with on the exact path: GMP's mpq_class wrapped without
// expression templates (so that a formula's intermediate types are values), with the leaves the formula
// templates take (`lift`: a double exactly; `difference`: v − w exactly). Doubles are read from their bits
// (rational_from_double.hpp), so the values are exact in any floating-point environment.
#pragma once

#include "core/rational_from_double.hpp"

#include <raykernel/core.hpp>

#include <gmpxx.h>

namespace raykernel::detail::exact {

struct Exact {
  mpq_class q;
};
inline Exact operator+(const Exact& a, const Exact& b) { return {a.q + b.q}; }
inline Exact operator-(const Exact& a, const Exact& b) { return {a.q - b.q}; }
inline Exact operator*(const Exact& a, const Exact& b) { return {a.q * b.q}; }
inline int sgn(const Exact& a) { return ::sgn(a.q); }

inline Exact lift(double x) { return {rational_from_double(x)}; }
inline Exact difference(double v, double w) { return {rational_from_double(v) - rational_from_double(w)}; }

// An exact rational as the public API gives it (raykernel::Rational: decimal strings in lowest terms; mpq_class is
// kept canonical, den ≥ 1).
inline ::raykernel::Rational to_public(const mpq_class& q) { return {q.get_num().get_str(), q.get_den().get_str()}; }

}  // namespace raykernel::detail::exact
