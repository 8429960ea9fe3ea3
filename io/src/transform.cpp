// io::exact_affine (<raykernel/io/transform.hpp>).
#include <raykernel/fp_environment.hpp>
#include <raykernel/io/transform.hpp>

#include <cmath>

namespace raykernel::io {

namespace {

// x·s when it is exact, else nothing. The product of the significands (each scaled into [1/2, 1) by a power of two,
// exactly) is exact iff its FMA residual is zero — representable there, far from underflow; scaling it back by
// 2^(ex + es) is exact iff scaling the result back again returns it (no bits lost to underflow, no overflow).
std::optional<double> exact_product(double x, double s) {
  if (x == 0 || s == 0) return x * s;
  int ex = 0, es = 0;
  const double xm = std::frexp(x, &ex), sm = std::frexp(s, &es);
  const double pm = xm * sm;
  if (std::fma(xm, sm, -pm) != 0) return std::nullopt;
  const double p = std::ldexp(pm, ex + es);
  if (!std::isfinite(p) || std::ldexp(p, -(ex + es)) != pm) return std::nullopt;
  return p;
}

}  // namespace

std::optional<double> exact_affine(double x, double scale, double translate) {
  const DefaultFpEnvironment environment;  // round to nearest: the FMA and TwoSum below mean what they say
  if (!std::isfinite(x) || !std::isfinite(scale) || !std::isfinite(translate)) return std::nullopt;
  const std::optional<double> product = exact_product(x, scale);
  if (!product) return std::nullopt;
  const double sum = *product + translate;
  const double t_part = sum - *product;
  const double error = (*product - (sum - t_part)) + (translate - t_part);  // TwoSum: exactly (product + t) − sum
  if (!std::isfinite(sum) || error != 0) return std::nullopt;
  return sum;
}

}  // namespace raykernel::io
