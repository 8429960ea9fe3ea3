// raykernel/io/transform.hpp: placing mesh vertices by an affine map exactly — or not at all.
//
// The readers (glTF's node transforms) and the CLI's scenes ("transform" of a mesh) apply a map to vertices only
// when every image is exact in doubles: a rounded vertex would not be the file's geometry, and the kernel's
// answers are exact for the doubles it is given. (A scene may instead ask for the images correctly rounded:
// raykernel::round_affine, <raykernel/core.hpp>.)
#pragma once

#include <optional>

namespace raykernel::io {

// x·scale + translate when both the product and the sum are exact doubles, else nothing: the product's residual
// is zero (an FMA on the significands, then the exponents: a product that loses bits to underflow is refused, a
// subnormal one that loses none is kept), the sum's TwoSum error is zero, and both are finite. Computed in the
// default floating-point environment whatever the caller's.
[[nodiscard]] std::optional<double> exact_affine(double x, double scale, double translate);

}  // namespace raykernel::io
