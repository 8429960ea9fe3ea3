// ctest proofs_half_gap: the C++ bit manipulation half_gap_to_nearer_neighbour (quotient_rounding.hpp)
// computes the model's half_gap (proofs/plane/QuotientRounding.v):
//   half_gap q = min(succ q − q, q − pred q) / 2,
// where succ and pred are the neighbouring doubles, i.e. std::nextafter towards ±inf. Checked for both
// signs, every exponent from −968 (the function's precondition, bounds::half_gap_min_magnitude;
// round_quotient_candidate_normal proves |q| ≥ 2^-900 wherever round_quotient certifies) to 1023, and
// several significands per exponent: the power of two, its successor, the largest significand and seeded
// pseudo-random ones.
#include "core/quotient_rounding.hpp"

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <random>

namespace {

double model_half_gap(double q) {
  const double up = std::nextafter(q, std::numeric_limits<double>::infinity()) - q;     // exact (Sterbenz)
  const double down = q - std::nextafter(q, -std::numeric_limits<double>::infinity());  // exact
  return std::fmin(up, down) / 2;  // exact: a normal power of two halved
}

}  // namespace

int main() {
  const std::uint64_t seed = 0x5eed'4a1f'9a9bULL;
  std::mt19937_64 random(seed);
  long checked = 0, failures = 0;
  for (int e = std::ilogb(raykernel::detail::bounds::half_gap_min_magnitude); e <= 1023; ++e) {
    const double base = std::ldexp(1.0, e);
    const double significands[] = {1.0, 1.0 + 0x1p-52, 2.0 - 0x1p-52, 1.5};
    auto check = [&](double q) {
      for (double x : {q, -q}) {
        ++checked;
        const double got = raykernel::detail::half_gap_to_nearer_neighbour(x);
        const double want = model_half_gap(x);
        if (got != want) {
          if (++failures <= 10)
            std::cerr << "FAIL: half_gap_to_nearer_neighbour(" << std::hexfloat << x << ") = " << got
                      << ", the model's half gap is " << want << std::defaultfloat << '\n';
        }
      }
    };
    for (double m : significands) check(m * base);
    for (int i = 0; i < 16; ++i) {
      const std::uint64_t fraction = random() >> 12;  // 52 random bits
      check((1.0 + std::ldexp(static_cast<double>(fraction), -52)) * base);
    }
  }
  std::cout << (failures == 0 ? "ok" : "FAILED") << ": " << checked << " values checked (seed 0x" << std::hex
            << seed << std::dec << "), " << failures << " mismatches\n";
  return failures == 0 ? 0 : 1;
}
