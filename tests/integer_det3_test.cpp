// core/integer_det3.hpp: the sign of x·(y × z) in fixed-width integers, and its value as at most four doubles,
// against GMP rationals (the doubles' exact values). Every certain answer must be the exact sign, and every
// expansion sum exactly to the determinant; on inputs inside the valid range (each vector's components integers
// over one power of two, below 2^62; for the expansion, the chunks' exponents in [−1074, 971]) the answer must be
// given, so that a routine that always gave up would fail; outside it (exponents 2^62 apart, NaN, infinities) it
// must give up.
#include "core/integer_det3.hpp"

#include "core/eft.hpp"

#include <raykernel/testkit/plane_queries.hpp>

#include <gtest/gtest.h>
#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace raykernel::detail {
namespace {

mpq_class exact_value(const double x[3], const double y[3], const double z[3]) {
  auto q = [](double v) { return mpq_class(v); };
  const mpq_class c0 = q(y[1]) * q(z[2]) - q(y[2]) * q(z[1]);
  const mpq_class c1 = q(y[2]) * q(z[0]) - q(y[0]) * q(z[2]);
  const mpq_class c2 = q(y[0]) * q(z[1]) - q(y[1]) * q(z[0]);
  return (q(x[0]) * c0 + q(x[1]) * c1) + q(x[2]) * c2;
}
int exact_sign(const double x[3], const double y[3], const double z[3]) { return sgn(exact_value(x, y, z)); }

// integer_det3_components: when it answers, at most four finite doubles, nonzero unless the only one, whose exact
// sum is the determinant. Returns whether it answered.
bool components_are_exact(const double x[3], const double y[3], const double z[3]) {
  Expansion<4> e;
  if (!integer_det3_components(integer_vector(x), integer_vector(y), integer_vector(z), e)) return false;
  EXPECT_GE(e.size, 1U);
  EXPECT_LE(e.size, 4U);
  mpq_class sum = 0;
  for (std::size_t i = 0; i < e.size; ++i) {
    EXPECT_TRUE(std::isfinite(e.component[i]));
    EXPECT_TRUE(e.component[i] != 0 || e.size == 1);
    if (i > 0) {
      EXPECT_LT(std::fabs(e.component[i - 1]), std::fabs(e.component[i]));  // increasing
    }
    sum += mpq_class(e.component[i]);
  }
  EXPECT_EQ(sum, exact_value(x, y, z));
  return true;
}

struct Draw {
  testkit::SplitMix64 rng{12345};
  std::uint64_t word() { return rng(); }
  std::int64_t integer(int bits) {  // uniform in (−2^bits, 2^bits)
    const std::int64_t m = static_cast<std::int64_t>(word() >> (64 - bits));
    return (word() & 1) != 0 ? -m : m;
  }
  int small(int lo, int hi) { return lo + static_cast<int>(word() % static_cast<std::uint64_t>(hi - lo + 1)); }
};

// Each vector: integers of up to `bits` bits times 2^e (one e per vector), so inside the range when bits ≤ 53.
void grid_vector(Draw& draw, int bits, int e, double v[3]) {
  for (int i = 0; i < 3; ++i) v[i] = std::ldexp(static_cast<double>(draw.integer(bits)), e);
}

TEST(IntegerDet3, GridDeterminantsAreCertainAndExact) {
  Draw draw;
  int zeros = 0;
  for (int n = 0; n < 200000; ++n) {
    double x[3], y[3], z[3];
    const int bits = draw.small(1, 53);
    grid_vector(draw, bits, draw.small(-1074 + 53, 900), x);
    grid_vector(draw, bits, draw.small(-1074 + 53, 900), y);
    grid_vector(draw, bits, draw.small(-1074 + 53, 900), z);
    if (n % 3 == 0) {  // an exact zero: z a multiple of y by a power of two
      const int k = draw.small(-4, 4);
      for (int i = 0; i < 3; ++i) z[i] = std::ldexp(y[i], k);
    }
    const Sign s = integer_det3_sign(x, y, z);
    ASSERT_TRUE(is_certain(s)) << "query " << n;
    ASSERT_EQ(static_cast<int>(s), exact_sign(x, y, z)) << "query " << n;
    zeros += s == Sign::zero;
  }
  EXPECT_GT(zeros, 60000);
}

TEST(IntegerDet3, GridDeterminantsAreExactExpansions) {
  // The same grids with exponents that keep every chunk in [−1074, 971] (each vector's in [−277, 270]: the lowest
  // chunk's exponent is at least −831, and |det| < 6·2^(3·323) < 2^972 bounds the highest): the expansion must be
  // given and exact; across the whole range, exact when given.
  Draw draw;
  int given = 0;
  for (int n = 0; n < 100000; ++n) {
    double x[3], y[3], z[3];
    const bool inside = n % 2 == 0;
    const int bits = draw.small(1, 53);
    auto exponent = [&] { return inside ? draw.small(-330 + 53, 270) : draw.small(-1074 + 53, 900); };
    grid_vector(draw, bits, exponent(), x);
    grid_vector(draw, bits, exponent(), y);
    grid_vector(draw, bits, exponent(), z);
    if (n % 3 == 0) {
      const int k = draw.small(-4, 4);
      for (int i = 0; i < 3; ++i) z[i] = std::ldexp(y[i], k);
    }
    const bool answered = components_are_exact(x, y, z);
    if (inside) {
      ASSERT_TRUE(answered) << "query " << n;
    }
    given += answered;
    if (::testing::Test::HasFailure()) FAIL() << "query " << n;
  }
  EXPECT_GT(given, 50000);
}

TEST(IntegerDet3, NearCancellationsAreExact) {
  // Determinants of ±1 and 0 among values of 52 bits: the products cancel to the last bit.
  Draw draw;
  for (int n = 0; n < 100000; ++n) {
    const double a = static_cast<double>(draw.integer(26)), b = static_cast<double>(draw.integer(26));
    const double x[3] = {1, 0, static_cast<double>(draw.small(-1, 1))};
    const double y[3] = {0, a, b + static_cast<double>(draw.small(-1, 1))};
    const double z[3] = {0, b, a};
    const Sign s = integer_det3_sign(x, y, z);
    ASSERT_TRUE(is_certain(s));
    ASSERT_EQ(static_cast<int>(s), exact_sign(x, y, z)) << a << " " << b;
    ASSERT_TRUE(components_are_exact(x, y, z)) << a << " " << b;
    if (::testing::Test::HasFailure()) FAIL() << a << " " << b;
  }
}

TEST(IntegerDet3, AnyDoublesGiveTheExactSignOrNothing) {
  // Random bit patterns within a few exponents of each other, and across the whole range: every certain answer
  // is the exact sign; within a vector spanning at most 9 binades above 53-bit significands it is certain.
  Draw draw;
  int certain = 0, expansions = 0;
  for (int n = 0; n < 200000; ++n) {
    double v[9];
    const int base = draw.small(-1074, 1000);
    const int spread = n % 2 == 0 ? 9 : 200;
    for (double& c : v) {
      const double m = 1.0 + static_cast<double>(draw.word() >> 12) * 0x1p-52;
      c = std::ldexp((draw.word() & 1) != 0 ? -m : m, std::min(1000, base + draw.small(0, spread)));
      if (draw.small(0, 9) == 0) c = 0.0;
    }
    const Sign s = integer_det3_sign(v, v + 3, v + 6);
    if (is_certain(s)) {
      ++certain;
      ASSERT_EQ(static_cast<int>(s), exact_sign(v, v + 3, v + 6)) << "query " << n;
    }
    const bool answered = components_are_exact(v, v + 3, v + 6);
    if (::testing::Test::HasFailure()) FAIL() << "query " << n;
    ASSERT_TRUE(!answered || is_certain(s)) << "query " << n;  // the same integers
    expansions += answered;
  }
  EXPECT_GT(certain, 50000);
  EXPECT_GT(expansions, 10000);
}

TEST(IntegerDet3, DyadicDoublesAreExact) {
  // ±c·2^q built from bits against ldexp (exact here: c < 2^53 and c·2^q representable), over the normal and
  // subnormal ranges and both ends of the valid range, and every width of c.
  Draw draw;
  for (int n = 0; n < 200000; ++n) {
    const int width = draw.small(1, 53);
    const std::uint64_t c = (draw.word() >> (64 - width)) | (std::uint64_t{1} << (width - 1));
    const int q = n % 4 == 0 ? draw.small(-1074, -1000) : n % 4 == 1 ? draw.small(900, 971) : draw.small(-1074, 971);
    const bool negative = (n & 8) != 0;
    const double expected = std::ldexp(negative ? -static_cast<double>(c) : static_cast<double>(c), q);
    ASSERT_EQ(dyadic_double(negative, c, q), expected) << c << " " << q;
    ASSERT_EQ(std::signbit(dyadic_double(negative, c, q)), negative);
  }
  EXPECT_EQ(dyadic_double(false, 1, -1074), 0x1p-1074);
  EXPECT_EQ(dyadic_double(false, (std::uint64_t{1} << 53) - 1, 971), std::numeric_limits<double>::max());
  EXPECT_EQ(dyadic_double(true, (std::uint64_t{1} << 52) - 1, -1074), -0x0.fffffffffffffp-1022);
  EXPECT_EQ(dyadic_double(false, std::uint64_t{1} << 52, -1074), 0x1p-1022);
}

TEST(IntegerDet3, GivesUpOutsideItsRange) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const double one[3] = {1, 2, 3}, other[3] = {4, 5, 7};
  const double with_inf[3] = {1, inf, 3}, with_nan[3] = {nan, 2, 3};
  EXPECT_EQ(integer_det3_sign(with_inf, one, other), Sign::uncertain);
  EXPECT_EQ(integer_det3_sign(one, with_nan, other), Sign::uncertain);
  // Components 2^62 apart in one vector: an aligned integer would need 63 bits.
  const double wide[3] = {1, 0x1p62, 3};
  EXPECT_EQ(integer_det3_sign(one, wide, other), Sign::uncertain);
  // 2^61 and an odd 1: 62 bits, still inside (|X| < 2^62).
  const double edge[3] = {1, 0x1p61, 3};
  EXPECT_EQ(static_cast<int>(integer_det3_sign(one, edge, other)), exact_sign(one, edge, other));
  // Subnormals and the largest doubles: exact in integers.
  const double tiny[3] = {0x1p-1074, 0x3p-1074, -0x5p-1074}, huge[3] = {0x1.fffffffffffffp1023, 0x1p1020, -0x1p1021};
  for (const double* a : {tiny, huge, one})
    for (const double* b : {tiny, huge, other}) {
      const Sign s = integer_det3_sign(a, b, one);
      ASSERT_TRUE(is_certain(s));
      EXPECT_EQ(static_cast<int>(s), exact_sign(a, b, one));
      components_are_exact(a, b, one);  // exact when given
    }
  // The expansion gives up where a chunk's double would be below 2^-1074 or overflow, not the sign: the
  // determinants of tiny, tiny2, one (about 2^-2141) and of huge, huge2, one (about 2^2040) are nonzero.
  const double tiny2[3] = {0x5p-1074, -0x1p-1074, 0x7p-1074}, huge2[3] = {0x1p1000, -0x1p1010, 0x1p1015};
  Expansion<4> e;
  ASSERT_NE(exact_sign(tiny, tiny2, one), 0);
  ASSERT_NE(exact_sign(huge, huge2, one), 0);
  EXPECT_FALSE(integer_det3_components(integer_vector(tiny), integer_vector(tiny2), integer_vector(one), e));
  EXPECT_FALSE(integer_det3_components(integer_vector(huge), integer_vector(huge2), integer_vector(one), e));
  EXPECT_FALSE(integer_det3_components(integer_vector(with_nan), integer_vector(one), integer_vector(other), e));
  EXPECT_FALSE(integer_det3_components(integer_vector(one), integer_vector(wide), integer_vector(other), e));
  // The zero determinant is the expansion {0}.
  ASSERT_TRUE(integer_det3_components(integer_vector(one), integer_vector(one), integer_vector(other), e));
  EXPECT_EQ(e.size, 1U);
  EXPECT_EQ(e.component[0], 0.0);
  // Signed zeros are zeros.
  const double zeros[3] = {-0.0, 0.0, -0.0};
  EXPECT_EQ(integer_det3_sign(zeros, one, other), Sign::zero);
}

// integer_vector_sum over TwoDiff's parts: X_i·2^E must be p_i − o_i exactly (rationals), whether or not the
// difference is a double, and be given when p and o span at most 7 binades above their significands.
mpq_class scaled(std::int64_t X, int E) {
  mpq_class r(static_cast<double>(X >> 32));  // X = hi·2^32 + lo: both exact as doubles
  r = r * mpq_class(4294967296.0) + mpq_class(static_cast<double>(X & 0xffffffff));
  mpq_class p = 1;
  mpz_class two = 2;
  if (E >= 0) {
    mpz_pow_ui(p.get_num_mpz_t(), two.get_mpz_t(), static_cast<unsigned long>(E));
  } else {
    mpz_pow_ui(p.get_den_mpz_t(), two.get_mpz_t(), static_cast<unsigned long>(-E));
  }
  return r * p;
}

TEST(IntegerDet3, DifferencesFromTwoPartsAreExact) {
  Draw draw;
  int given = 0, inexact = 0;
  for (int n = 0; n < 200000; ++n) {
    double p[3], o[3], parts[6];  // h_0, h_1, h_2, l_0, l_1, l_2
    const int base = draw.small(-1074, 1000);
    const int spread = n % 2 == 0 ? 7 : 120;  // 7: |p − o| < 2^(base + 9), parts ≥ 2^(base − 52): 61 bits
    for (int i = 0; i < 3; ++i) {
      for (double* v : {p, o}) {
        const double m = 1.0 + static_cast<double>(draw.word() >> 12) * 0x1p-52;
        const bool negative = (draw.word() & 1) != 0;
        const int e = std::min(1000, base + draw.small(0, spread));
        v[i] = std::ldexp(negative ? -m : m, e);
        if (draw.small(0, 9) == 0) v[i] = 0.0;
      }
      const DoubleDouble s = two_diff(p[i], o[i]);
      parts[i] = s.hi;
      parts[i + 3] = s.lo;
      inexact += s.lo != 0;
    }
    const IntegerVector X = integer_vector_sum(parts);
    bool finite = true;
    for (int i = 0; i < 3; ++i) finite = finite && std::isfinite(parts[i]) && std::isfinite(parts[i + 3]);
    if (n % 2 == 0 && finite) {
      ASSERT_TRUE(X.ok) << "query " << n;
    }
    if (!X.ok) continue;
    ++given;
    for (int i = 0; i < 3; ++i) {
      ASSERT_LT(X.v[i] < 0 ? -X.v[i] : X.v[i], std::int64_t{1} << 62);
      ASSERT_EQ(scaled(X.v[i], X.exponent), mpq_class(p[i]) - mpq_class(o[i])) << "query " << n << " component " << i;
    }
  }
  EXPECT_GT(given, 100000);
  EXPECT_GT(inexact, 100000);  // most differences are not doubles: the low parts matter
}

TEST(IntegerDet3, DifferencesGiveUpOutsideTheirRange) {
  // 1 − 2^-70: the parts 1 and −2^-70 are 70 binades apart (an aligned part of 2^70).
  const double parts_wide[6] = {1, 0, 0, -0x1p-70, 0, 0};
  EXPECT_FALSE(integer_vector_sum(parts_wide).ok);
  // Two aligned parts below 2^62, read over 2^0: their sum below 2^62 is kept, one reaching 2^62 is refused.
  const double parts_sum[6] = {0x1p61, 1, 0, 0x1.ffffffffffffep60, 0, 0};
  const IntegerVector s = integer_vector_sum(parts_sum);
  EXPECT_TRUE(s.ok);  // 2^61 + 2^61 − 2^9 < 2^62
  const double parts_over[6] = {0x1.ffffffffffffep61, 1, 0, 0x1.ffffffffffffep61, 0, 0};
  EXPECT_FALSE(integer_vector_sum(parts_over).ok);  // 2·(2^62 − 2^10) ≥ 2^62
  const double parts_nan[6] = {1, 2, 3, 0, std::numeric_limits<double>::quiet_NaN(), 0};
  EXPECT_FALSE(integer_vector_sum(parts_nan).ok);
  // Exact values where it answers: 2^61 + 2^61 − 2^9 and 1.
  EXPECT_EQ(s.exponent, 0);
  EXPECT_EQ(s.v[0], (std::int64_t{1} << 62) - 512);
  EXPECT_EQ(s.v[1], 1);
  EXPECT_EQ(s.v[2], 0);
}

}  // namespace
}  // namespace raykernel::detail
