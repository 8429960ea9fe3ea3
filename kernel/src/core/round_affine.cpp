// round_affine (<raykernel/core.hpp>): RN(row·v + c), the exact value rounded once — for transforms that cannot be
// applied exactly (a rotation of a mesh in a scene), where the correctly rounded image is the honest answer.
//
// The exact value as a GMP rational (each double decoded from its bits, core/rational_from_double.hpp), rounded by
// the one rounding of rationals to binary64 (core/binary64_rounding.hpp), in the default floating-point
// environment whatever the caller's. A microsecond or so per coordinate: it runs once per vertex of a scene's mesh.
#include "core/binary64_rounding.hpp"
#include "core/fp_environment.hpp"
#include "core/rational_from_double.hpp"

#include <raykernel/core.hpp>

#include <cmath>
#include <stdexcept>

namespace raykernel {

double round_affine(const Vec3& row, const Vec3& v, double c) {
  const double r[3] = {row.x, row.y, row.z}, x[3] = {v.x, v.y, v.z};
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(r[i]) || !std::isfinite(x[i])) throw std::invalid_argument("round_affine: a value is not finite");
  if (!std::isfinite(c)) throw std::invalid_argument("round_affine: a value is not finite");
  return detail::in_default_fp_environment([&] {
    mpq_class q = detail::exact::rational_from_double(c);
    for (int i = 0; i < 3; ++i)
      q += detail::exact::rational_from_double(r[i]) * detail::exact::rational_from_double(x[i]);
    return detail::exact::round_rational_to_nearest_even(q);
  });
}

}  // namespace raykernel
