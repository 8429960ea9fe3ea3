// core/validation.hpp's predicates against their definition: a ray, plane or triangle is valid when every
// component is finite (std::isfinite, the oracle, independent of the bit reduction all_finite uses) and, for a
// ray or plane, its direction or normal is not (±0, ±0, ±0). Every component position gets every class of double
// that could confuse a bit test: ±inf, quiet and signalling NaNs with either sign and payload, the largest finite,
// the smallest normal and subnormal, ±0, and random finite patterns.
#include "core/validation.hpp"

#include <raykernel/testkit/plane_queries.hpp>

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace raykernel::detail {
namespace {

std::vector<double> special_values() {
  using L = std::numeric_limits<double>;
  return {L::infinity(), -L::infinity(), L::quiet_NaN(), -L::quiet_NaN(), L::signaling_NaN(),
          std::bit_cast<double>(std::uint64_t{0x7FF0000000000001}), std::bit_cast<double>(std::uint64_t{0xFFFFFFFFFFFFFFFF}),
          L::max(), -L::max(), L::min(), -L::min(), L::denorm_min(), -L::denorm_min(), 0.0, -0.0, 1.0, -2.5,
          std::bit_cast<double>(std::uint64_t{0x7FEFFFFFFFFFFFFF}), std::bit_cast<double>(std::uint64_t{0x000FFFFFFFFFFFFF})};
}

template <std::size_t N>
bool finite_by_definition(const std::array<double, N>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

bool zero_by_definition(double x, double y, double z) { return x == 0 && y == 0 && z == 0; }

TEST(Validation, EveryComponentOfEveryKindAgainstTheDefinition) {
  testkit::SplitMix64 rng(2026);
  const std::vector<double> specials = special_values();
  long checked = 0, invalid = 0;
  for (int round = 0; round < 200; ++round) {
    std::array<double, 15> base;
    for (double& x : base) {
      do x = std::bit_cast<double>(rng()); while (!std::isfinite(x));
    }
    for (std::size_t position = 0; position < base.size(); ++position) {
      for (double s : specials) {
        std::array<double, 15> v = base;
        v[position] = s;
        if (round % 3 == 0) v[(position + 7) % 15] = specials[static_cast<std::size_t>(round) % specials.size()];
        const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
        const Plane plane{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
        const Triangle triangle{{v[6], v[7], v[8]}, {v[9], v[10], v[11]}, {v[12], v[13], v[14]}};
        const std::array<double, 6> r{v[0], v[1], v[2], v[3], v[4], v[5]};
        const std::array<double, 9> t{v[6], v[7], v[8], v[9], v[10], v[11], v[12], v[13], v[14]};
        const bool ray_valid = finite_by_definition(r) && !zero_by_definition(v[3], v[4], v[5]);
        ASSERT_EQ(is_valid(ray), ray_valid) << "position " << position << ", value " << s;
        ASSERT_EQ(is_valid(plane), ray_valid) << "position " << position << ", value " << s;
        ASSERT_EQ(is_valid(triangle), finite_by_definition(t)) << "position " << position << ", value " << s;
        ASSERT_EQ(is_finite(Vec3{v[0], v[1], v[2]}), finite_by_definition(std::array<double, 3>{v[0], v[1], v[2]}));
        ++checked;
        invalid += ray_valid ? 0 : 1;
      }
    }
  }
  // Both answers occur (a predicate that always said yes or always no would fail above).
  EXPECT_GT(invalid, 0);
  EXPECT_LT(invalid, checked);
}

TEST(Validation, ZeroDirectionsAndNormalsInEveryZeroSign) {
  for (int signs = 0; signs < 8; ++signs) {
    const Vec3 zero{signs & 1 ? -0.0 : 0.0, signs & 2 ? -0.0 : 0.0, signs & 4 ? -0.0 : 0.0};
    EXPECT_FALSE(is_valid(Ray{{1, 2, 3}, zero}));
    EXPECT_FALSE(is_valid(Plane{{1, 2, 3}, zero}));
    // A subnormal component is not zero (DAZ would say it is: the predicates read bits).
    Vec3 tiny = zero;
    tiny.y = std::numeric_limits<double>::denorm_min();
    EXPECT_TRUE(is_valid(Ray{{1, 2, 3}, tiny}));
    EXPECT_TRUE(is_valid(Plane{{1, 2, 3}, tiny}));
  }
}

}  // namespace
}  // namespace raykernel::detail
