// The shared pieces of the testkit's exact constructions (triangle_queries.cpp, sphere_queries.cpp): integer
// vectors (exact in int64 while |coordinate| < 2^45 or so), the Draw that turns a BitSource's words into
// integers, coins and doubles, and moving a double by ulps. Internal to the testkit.
#pragma once

#include <raykernel/testkit/plane_queries.hpp>

#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace raykernel::testkit::construction {

struct IVec {
  std::int64_t x, y, z;
};
inline IVec operator+(IVec a, IVec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline IVec operator-(IVec a, IVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline IVec operator*(std::int64_t s, IVec a) { return {s * a.x, s * a.y, s * a.z}; }
inline IVec cross(IVec a, IVec b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline bool is_zero(IVec a) { return a.x == 0 && a.y == 0 && a.z == 0; }

class Draw {
 public:
  explicit Draw(const BitSource& bits) : bits_(bits) {}
  std::uint64_t word() { return bits_(); }
  bool coin() { return (word() & 1) != 0; }
  // Uniform in [lo, hi], hi − lo < 2^62.
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    return lo + static_cast<std::int64_t>(word() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  int small(int lo, int hi) { return static_cast<int>(integer(lo, hi)); }
  IVec ivec(std::int64_t limit) { return {integer(-limit, limit), integer(-limit, limit), integer(-limit, limit)}; }
  // A multiple of 2^-53 uniform in [-1, 1).
  double unit() {
    return static_cast<double>(static_cast<std::int64_t>(word() >> 10) - (std::int64_t{1} << 53)) * 0x1p-53;
  }
  Vec3 unit_vector() { return {unit(), unit(), unit()}; }
  double scaled(int emin, int emax) {
    const double significand = 1.0 + static_cast<double>(word() >> 12) * 0x1p-52;
    const double magnitude = std::ldexp(significand, small(emin, emax));
    return coin() ? -magnitude : magnitude;
  }

 private:
  const BitSource& bits_;
};

// x moved by k units in the last place (toward +inf for k > 0).
inline double nudge(double x, int k) {
  for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
  return x;
}
inline double& component(Vec3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

// One random permutation and reflection of the axes (a permutation, then three coins), applied to every vector
// given: differences, dot and cross products keep their magnitudes exactly (a reflection flips the orientation).
inline void permute_and_reflect_axes(Draw& draw, std::initializer_list<Vec3*> vectors) {
  const int permutation[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* perm = permutation[draw.small(0, 5)];
  const bool flip[3] = {draw.coin(), draw.coin(), draw.coin()};
  for (Vec3* v : vectors) {
    Vec3 s{};
    for (int i = 0; i < 3; ++i) {
      const double c = component(*v, perm[i]);
      component(s, i) = flip[i] ? -c : c;
    }
    *v = s;
  }
}

}  // namespace raykernel::testkit::construction
