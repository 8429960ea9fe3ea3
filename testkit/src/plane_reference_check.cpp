// The reference check (reference_check.hpp): the exact answer from intersect_exact_rational, the ulp
// distance from the bits of the doubles.
#include <raykernel/testkit/plane_reference_check.hpp>

#include "default_environment.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <ostream>
#include <sstream>

namespace raykernel::testkit {
namespace {

using internal::DefaultEnvironmentScope;

// The position of x in the increasing order of all non-NaN doubles, -inf → 0x000fffffffffffff ... -0 →
// 2^63 − 1, +0 → 2^63, ... +inf → 2^63 + 0x7ff0000000000000: consecutive doubles get consecutive keys
// (IEEE-754 orders the magnitudes of same-signed values like their bit patterns, §3.4), and the two zeros
// get two keys. Every key fits in 64 bits, and differences of keys are exact ulp distances.
std::uint64_t order_key(double x) noexcept {
  const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
  constexpr std::uint64_t sign = std::uint64_t{1} << 63;
  return (bits & sign) != 0 ? (sign - 1) - (bits & ~sign) : sign + bits;
}

// An integer in decimal, its middle elided when it is long: num and den of subnormal or huge inputs have
// hundreds of digits, and exact_num/exact_den keep them in full.
std::string abbreviated(const std::string& digits) {
  constexpr std::size_t keep_front = 24, keep_back = 12;
  if (digits.size() <= keep_front + keep_back + 20) return digits;
  const std::size_t count = digits.size() - (digits[0] == '-' ? 1 : 0);
  return digits.substr(0, keep_front) + "...(" + std::to_string(count) + " digits)..." +
         digits.substr(digits.size() - keep_back);
}

// "P/Q", or "P" when Q is 1, long integers abbreviated.
std::string rational_string(const Rational& r) {
  return r.denominator == "1" ? abbreviated(r.numerator) : abbreviated(r.numerator) + "/" + abbreviated(r.denominator);
}

std::string relation_name(const Intersection& x) { return std::string(to_string(x.relation)); }

std::string pad(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

std::string describe_t(double t) {
  if (std::isnan(t)) return "nan";
  return hex_string(t) + " (" + shortest_decimal(t) + ")";
}

}  // namespace

std::optional<std::uint64_t> ulp_distance(double a, double b) noexcept {
  if (std::isnan(a) || std::isnan(b)) return std::nullopt;
  const std::uint64_t ka = order_key(a), kb = order_key(b);
  return ka > kb ? ka - kb : kb - ka;
}

std::optional<std::int64_t> ulp_difference(double a, double b) noexcept {
  const std::optional<std::uint64_t> distance = ulp_distance(a, b);
  if (!distance) return std::nullopt;
  constexpr std::uint64_t limit = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
  const std::int64_t magnitude = static_cast<std::int64_t>(*distance < limit ? *distance : limit);
  return order_key(b) < order_key(a) ? -magnitude : magnitude;
}

std::string hex_string(double x) {
  if (std::isnan(x)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}

std::string shortest_decimal(double x) {
  if (std::isnan(x)) return "nan";
  char buf[64];
  const auto result = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip form
  return std::string(buf, result.ptr);
}

std::string to_string(const Query& q) {
  auto v = [](const char* name, const Vec3& a) {
    return std::string(name) + " = (" + hex_string(a.x) + ", " + hex_string(a.y) + ", " + hex_string(a.z) + ")";
  };
  return v("o", q.ray.origin) + "  " + v("d", q.ray.direction) + "  " + v("p", q.plane.point) + "  " +
         v("n", q.plane.normal);
}

std::string classify_line(const Query& q) {
  std::string line;
  for (const Vec3* v : {&q.ray.origin, &q.ray.direction, &q.plane.point, &q.plane.normal}) {
    for (double c : {v->x, v->y, v->z}) {
      if (!line.empty()) line += ' ';
      line += hex_string(c);
    }
  }
  return line;
}

ReferenceCheck check_against_reference(const Query& query, const Intersection& got, std::uint64_t max_t_ulps) {
  const DefaultEnvironmentScope environment;
  const ExactIntersection exact = intersect_exact_rational(query.ray, query.plane);  // throws invalid_input
  ReferenceCheck c;
  c.query = query;
  c.expected = exact.intersection;
  c.got = got;
  c.exact_num = exact.num;
  c.exact_den = exact.den;
  c.exact_t = exact.t;
  c.max_t_ulps = max_t_ulps;
  c.relation_matches = got.relation == exact.intersection.relation;
  c.t_compared = exact.intersection.relation == Relation::hit || exact.intersection.relation == Relation::behind;
  if (c.t_compared) {
    if (const auto diff = ulp_difference(c.expected.t, got.t)) {
      c.t_ulps = ulp_distance(c.expected.t, got.t);
      c.t_direction = (*diff > 0) - (*diff < 0);
    }
  }
  return c;
}

ReferenceCheck check_against_reference(const Query& query, Relation relation, double t, std::uint64_t max_t_ulps) {
  return check_against_reference(query, Intersection{relation, t}, max_t_ulps);
}

std::string ReferenceCheck::report() const {
  const DefaultEnvironmentScope environment;
  std::ostringstream os;
  os << "raykernel reference check " << (passed() ? "passed" : "FAILED");
  if (!passed()) {
    os << ": ";
    if (!relation_matches) {
      os << "relation is " << to_string(got.relation) << ", expected " << to_string(expected.relation)
         << (t_matches() ? "" : "; ");
    }
    if (!t_matches()) {
      if (t_ulps) {
        os << "t is " << *t_ulps << (*t_ulps == 1 ? " ulp " : " ulps ") << (t_direction < 0 ? "below" : "above")
           << " the correctly rounded t";
      } else {
        os << "t is nan, expected a number";
      }
      os << " (tolerance " << max_t_ulps << (max_t_ulps == 1 ? " ulp)" : " ulps)");
    }
  }
  os << '\n';
  const std::size_t w = std::max(relation_name(expected).size(), relation_name(got).size()) + 1;
  os << "  query     " << to_string(query) << '\n';
  os << "  replay    echo '" << classify_line(query) << "' | raykernel classify --exact-t --hex\n";
  auto answer = [&](const Intersection& x, bool show_t) {
    std::string s = pad(relation_name(x), w);
    if (show_t) s += "t = " + describe_t(x.t);
    return s;
  };
  // The got t is shown whenever it is not NaN, even where no t is expected: it is what the code returned.
  os << "  expected  " << answer(expected, t_compared) << '\n';
  os << "  got       " << answer(got, t_compared || !std::isnan(got.t)) << '\n';
  os << "  exact     ";
  if (exact_t) os << "t = num/den = " << exact_t->str() << ", ";
  os << "num = " << rational_string(exact_num) << ", den = " << rational_string(exact_den) << '\n';
  if (t_compared && t_ulps) {
    os << "  t error   " << *t_ulps << (*t_ulps == 1 ? " ulp" : " ulps");
    if (*t_ulps != 0) os << (t_direction < 0 ? " below" : " above");
    os << " (tolerance " << max_t_ulps << ")\n";
  }
  return os.str();
}

std::ostream& operator<<(std::ostream& os, const ReferenceCheck& check) { return os << check.report(); }

}  // namespace raykernel::testkit
