// Constructions of hard queries. Where a construction promises an exact property (d·n = 0, a rounding tie),
// every coordinate is an integer below 2^53 times a power of two, so the doubles hold it exactly; the
// exact stage of raykernel checks each promise in tests/plane_queries_test.cpp.
#include <raykernel/testkit/plane_queries.hpp>

#include <cmath>
#include <cstdint>
#include <utility>

namespace raykernel::testkit {
namespace {

class Draw {
 public:
  explicit Draw(const BitSource& bits) : bits_(bits) {}

  std::uint64_t word() { return bits_(); }
  bool coin() { return (word() & 1) != 0; }
  // Uniform in [lo, hi] (inclusive), hi − lo < 2^32.
  int integer(int lo, int hi) {
    return lo + static_cast<int>(word() % static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1));
  }
  // A multiple of 2^-53 uniform in [-1, 1): exact, with 54 random bits.
  double unit() {
    return static_cast<double>(static_cast<std::int64_t>(word() >> 10) - (std::int64_t{1} << 53)) * 0x1p-53;
  }
  // ±(1 + f)·2^e, f a random 52-bit fraction, e uniform in [emin, emax] (rounded once by ldexp when the
  // result is subnormal; never zero for emin ≥ -1074).
  double scaled(int emin, int emax) {
    const double significand = 1.0 + static_cast<double>(word() >> 12) * 0x1p-52;
    const double magnitude = std::ldexp(significand, integer(emin, emax));
    return coin() ? -magnitude : magnitude;
  }

  Vec3 unit_vector_box() { return nonzero({unit(), unit(), unit()}); }
  Vec3 scaled_vector(int emin, int emax) { return {scaled(emin, emax), scaled(emin, emax), scaled(emin, emax)}; }
  Vec3 integer_vector(int limit) {
    return {static_cast<double>(integer(-limit, limit)), static_cast<double>(integer(-limit, limit)),
            static_cast<double>(integer(-limit, limit))};
  }

  static Vec3 nonzero(Vec3 v) {
    if (v.x == 0 && v.y == 0 && v.z == 0) v.x = 1;
    return v;
  }

 private:
  const BitSource& bits_;
};

Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec3 a, Vec3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
bool is_zero(Vec3 a) { return a.x == 0 && a.y == 0 && a.z == 0; }
Vec3 scale_by_power_of_two(Vec3 a, int e) { return {std::ldexp(a.x, e), std::ldexp(a.y, e), std::ldexp(a.z, e)}; }
double& component(Vec3& v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }

// x moved by k units in the last place (toward +inf for k > 0).
double nudge(double x, int k) {
  for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
  return x;
}

// The same coordinate permutation and per-coordinate sign flips applied to all four vectors: dot products
// and differences are unchanged exactly, so every promised property survives, while the hard direction
// moves off the x axis.
Query shuffle_axes(Draw& draw, Query q) {
  const int permutation[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* perm = permutation[draw.integer(0, 5)];
  const bool flip[3] = {draw.coin(), draw.coin(), draw.coin()};
  for (Vec3* v : {&q.ray.origin, &q.ray.direction, &q.plane.point, &q.plane.normal}) {
    Vec3 shuffled{};
    for (int i = 0; i < 3; ++i) {
      const double c = component(*v, perm[i]);
      component(shuffled, i) = flip[i] ? -c : c;
    }
    *v = shuffled;
  }
  return q;
}

// A nonzero integer vector orthogonal to n (n ≠ 0, integer): n × w for a random w, or n × e_k.
Vec3 orthogonal_integer_vector(Draw& draw, Vec3 n, int limit) {
  Vec3 v = cross(n, draw.integer_vector(limit));
  for (Vec3 axis : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    if (!is_zero(v)) break;
    v = cross(n, axis);
  }
  return v;
}

// Exact degeneracies from integers: n, the in-plane vectors, p and o are integers below 2^22 times powers
// of two, so d·n and (p − o)·n are exact. `off_plane` is the multiple of n added to o (0: o on the plane).
Query integer_plane_query(Draw& draw, bool direction_in_plane, int off_plane, int exponent_range) {
  const Vec3 n = Draw::nonzero(draw.integer_vector(64));
  const Vec3 direction = direction_in_plane ? orthogonal_integer_vector(draw, n, 64) : draw.unit_vector_box();
  const Vec3 in_plane = orthogonal_integer_vector(draw, n, 64);
  const Vec3 p = draw.integer_vector(1 << 20);
  const Vec3 o = p + static_cast<double>(draw.integer(-8, 8)) * in_plane + static_cast<double>(off_plane) * n;
  const int point_scale = draw.integer(-exponent_range, exponent_range);
  return {{scale_by_power_of_two(o, point_scale),
           direction_in_plane ? scale_by_power_of_two(direction, draw.integer(-exponent_range, exponent_range))
                              : direction},
          {scale_by_power_of_two(p, point_scale), scale_by_power_of_two(n, draw.integer(-exponent_range, exponent_range))}};
}

// t = num/den = ±M·2^s with M an odd 54-bit integer: exactly halfway between two doubles. den = D·2^a
// with D odd, so num = D·M·2^(s+a) needs up to 58 bits and is held as p_x − o_x = hi − (−lo).
// near_tie_bits > 0 adds ±2^(s+a−near_tie_bits) to num through the y coordinate.
Query tie_query(Draw& draw, int near_tie_bits) {
  const std::uint64_t M = (std::uint64_t{1} << 53) + 2 * (draw.word() >> 12) + 1;  // odd, in (2^53, 2^54)
  const std::uint64_t D = 2 * static_cast<std::uint64_t>(draw.integer(0, 7)) + 1;   // odd, 1..15
  const std::uint64_t X = D * M;                                                     // < 2^58
  const double hi = static_cast<double>(X);
  const double lo = static_cast<double>(static_cast<std::int64_t>(X) - static_cast<std::int64_t>(hi));
  const int s = draw.integer(-113, -13);  // t in [2^-60, 2^41)
  const int a = draw.integer(-20, 20);
  const int b = draw.integer(-20, 20);
  const double same_y = draw.unit(), same_z = draw.unit();
  Query q{{{-std::ldexp(lo, s + a - b), same_y, same_z}, {std::ldexp(static_cast<double>(D), a - b), 0, 0}},
          {{std::ldexp(hi, s + a - b), same_y, same_z},
           {std::ldexp(1.0, b), static_cast<double>(draw.integer(-9, 9)), static_cast<double>(draw.integer(-9, 9))}}};
  if (near_tie_bits > 0) {
    q.plane.normal.y = 1;
    q.ray.origin.y = 0;
    q.plane.point.y = std::ldexp(draw.coin() ? 1.0 : -1.0, s + a - near_tie_bits);
  }
  if (draw.coin()) q.ray.direction.x = -q.ray.direction.x;  // t < 0: behind
  return q;
}

// t = ±(2^m + j)/2^m·2^(s−u) with j in (2^(m−54), 2^(m−53)): t lies in (2^e + ulp/4, 2^e + ulp/2) for e = s − u
// and rounds down to ±2^e, where the gap below 2^e is half the gap above (round_quotient's conservative rule
// cannot certify it; the rounding boundaries can). num = (p − o)·n = (2^m + j)·2^s with p_x = 2^(m+s),
// o_x = −j·2^s and o, p equal in y and z; den = d·n = ±2^(m+u) with d along x and n_x = 1.
Query above_power_of_two_query(Draw& draw) {
  const int m = draw.integer(55, 100);
  const std::uint64_t low = std::uint64_t{1} << (m - 54);
  const double j = static_cast<double>(low + 1 + draw.word() % (low - 1));  // in (2^(m−54), 2^(m−53))
  const int s = draw.integer(-60, 60), u = draw.integer(-60, 60);
  const double same_y = draw.unit(), same_z = draw.unit();
  Query q{{{-std::ldexp(j, s), same_y, same_z}, {std::ldexp(draw.coin() ? 1.0 : -1.0, m + u), 0, 0}},
          {{std::ldexp(1.0, m + s), same_y, same_z},
           {1, static_cast<double>(draw.integer(-9, 9)), static_cast<double>(draw.integer(-9, 9))}}};
  return q;
}

Query build(QueryKind kind, Draw& draw) {
  switch (kind) {
    case QueryKind::random:
      return {{draw.unit_vector_box(), draw.unit_vector_box()}, {draw.unit_vector_box(), draw.unit_vector_box()}};
    case QueryKind::wide_exponents:
      return {{draw.scaled_vector(-300, 300), draw.scaled_vector(-300, 300)},
              {draw.scaled_vector(-300, 300), draw.scaled_vector(-300, 300)}};
    case QueryKind::near_parallel: {
      const Vec3 n = draw.unit_vector_box();
      const Vec3 d0 = draw.unit_vector_box();
      Vec3 d = d0 - (dot(d0, n) / dot(n, n)) * n;  // orthogonal to n up to rounding
      const int k = draw.integer(0, 2);
      component(d, k) = nudge(component(d, k), draw.integer(-4, 4));
      return {{draw.unit_vector_box(), Draw::nonzero(d)}, {draw.unit_vector_box(), n}};
    }
    case QueryKind::near_coplanar: {
      const Vec3 p = draw.unit_vector_box();
      const Vec3 n = draw.unit_vector_box();
      const Vec3 a = draw.unit_vector_box();
      Vec3 o = p + (a - (dot(a, n) / dot(n, n)) * n);  // on the plane up to rounding
      const int k = draw.integer(0, 2);
      component(o, k) = nudge(component(o, k), draw.integer(-4, 4));
      return {{o, draw.unit_vector_box()}, {p, n}};
    }
    case QueryKind::exact_parallel: {
      int m = draw.integer(1, 8);
      if (draw.coin()) m = -m;
      return integer_plane_query(draw, true, m, 200);
    }
    case QueryKind::exact_in_plane: return integer_plane_query(draw, true, 0, 200);
    case QueryKind::origin_on_plane: return integer_plane_query(draw, false, 0, 40);
    case QueryKind::rounding_tie: return tie_query(draw, 0);
    case QueryKind::near_tie: return tie_query(draw, draw.integer(20, 60));
    case QueryKind::above_power_of_two: return above_power_of_two_query(draw);
    case QueryKind::subnormal:
      return {{draw.scaled_vector(-1074, -400), draw.scaled_vector(-1074, -400)},
              {draw.scaled_vector(-1074, -400), draw.scaled_vector(-1074, -400)}};
    case QueryKind::huge_products:
      return {{draw.scaled_vector(400, 1023), draw.scaled_vector(400, 1023)},
              {draw.scaled_vector(400, 1023), draw.scaled_vector(400, 1023)}};
    case QueryKind::t_overflow: {
      // den ≈ 2^-a·2^-b, num ≈ 2^c·2^-b: t ≈ 2^(a+c) with a + c in [900, 1120].
      const int a = draw.integer(900, 1020), b = draw.integer(-100, 100), c = draw.integer(0, 100);
      return {{scale_by_power_of_two(draw.unit_vector_box(), c), scale_by_power_of_two(draw.unit_vector_box(), -a)},
              {scale_by_power_of_two(draw.unit_vector_box(), c), scale_by_power_of_two(draw.unit_vector_box(), -b)}};
    }
    case QueryKind::t_underflow: {
      const int c = draw.integer(960, 1074);  // p, o ≈ 2^-c: (p − o)·n underflows; t ≈ 2^-(c + a)
      return {{scale_by_power_of_two(draw.unit_vector_box(), -c),
               scale_by_power_of_two(draw.unit_vector_box(), draw.integer(0, 100))},
              {scale_by_power_of_two(draw.unit_vector_box(), -c),
               scale_by_power_of_two(draw.unit_vector_box(), -draw.integer(0, 100))}};
    }
  }
  return {{{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}};
}

}  // namespace

std::string_view to_string(QueryKind kind) noexcept {
  switch (kind) {
    case QueryKind::random: return "random";
    case QueryKind::wide_exponents: return "wide-exponents";
    case QueryKind::near_parallel: return "near-parallel";
    case QueryKind::near_coplanar: return "near-coplanar";
    case QueryKind::exact_parallel: return "exact-parallel";
    case QueryKind::exact_in_plane: return "exact-in-plane";
    case QueryKind::origin_on_plane: return "origin-on-plane";
    case QueryKind::rounding_tie: return "rounding-tie";
    case QueryKind::near_tie: return "near-tie";
    case QueryKind::subnormal: return "subnormal";
    case QueryKind::huge_products: return "huge-products";
    case QueryKind::t_overflow: return "t-overflow";
    case QueryKind::t_underflow: return "t-underflow";
    case QueryKind::above_power_of_two: return "above-power-of-two";
  }
  return "?";
}

Query make_query(QueryKind kind, const BitSource& bits) {
  Draw draw(bits);
  Query q = build(kind, draw);
  q = shuffle_axes(draw, q);
  // Only the uniform kinds can draw a zero vector (with probability 2^-162, or when a shrinker tries all
  // zero words); the query must stay valid input.
  q.ray.direction = Draw::nonzero(q.ray.direction);
  q.plane.normal = Draw::nonzero(q.plane.normal);
  return q;
}

}  // namespace raykernel::testkit
