// fuzz_spawn: one spawn or spawn_to query per input (docs/contract.md §9), answered by raykernel's `spawn` and
// `spawn_to` in binary64 and binary32, and checked against the definition by an oracle in GMP rationals written
// here (nothing shared with the kernel): P exactly, σ and s exactly, P̂ verified as the rounding to nearest-even
// of P in the format (exact comparisons with the neighbouring values), the stepped coordinate k values of the
// format away from P̂_i along the axis of the largest |N_i| in direction sign(N_i)·s, σ(origin) = s, and the
// value one step back (k ≥ 1) not on side s — so k is the smallest, and the new ray from the origin meets the
// source triangle's plane only at t < 0. spawn's certified fast path is also checked against spawn_exact (the exact
// path alone): the same origin bit for bit, or the same reason.
//
// Input: byte 0 is the mode (bit 0: binary32; bit 1: spawn_to, the last three numbers the target q; bit 2: the
// hit point given as a point, the first three numbers; bit 7: structured numbers), then 18 numbers: raw
// doubles (8 bytes each, every bit pattern), or with bit 7 small integers scaled by powers of two (2 bytes of
// integer and 1 of exponent each), where hit points on the plane, ties of |N_i| and rounding midpoints are common.
//
// Invalid input: spawn throws invalid_input exactly when the oracle finds a reason it names (a non-finite value,
// a zero d or w, N = 0, den = 0, w·N = 0, σ(q) = 0, a P̂ beyond the format, no value of the format on the side);
// the last two are checked from the oracle's own P and threshold.
#include "fuzz_exact.hpp"
#include "fuzz_support.hpp"

#include <raykernel/spawn.hpp>

#include <gmpxx.h>

#include <array>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string>

namespace {

using raykernel::Vec3;
using raykernel::fuzz::check;
using raykernel::fuzz::exact_of;
using raykernel::fuzz::power_of_two;

struct Input {
  std::uint8_t mode = 0;
  std::array<double, 18> v{};
};
Input current;

std::string describe_current() {
  std::string s = "mode " + std::to_string(current.mode) + ":";
  for (double x : current.v) s += " " + raykernel::fuzz::hex(x);
  return s;
}

Input decode(std::span<const std::uint8_t> bytes) {
  Input in;
  if (bytes.empty()) return in;
  in.mode = bytes[0];
  bytes = bytes.subspan(1);
  const bool structured = (in.mode & 0x80) != 0;
  const std::size_t width = structured ? 3 : 8;
  for (std::size_t k = 0; k < in.v.size(); ++k) {
    std::array<std::uint8_t, 8> b{};
    for (std::size_t j = 0; j < width; ++j) {
      const std::size_t at = k * width + j;
      b[j] = at < bytes.size() ? bytes[at] : 0;
    }
    if (structured) {
      const auto m = static_cast<std::int16_t>(b[0] | (b[1] << 8));
      const int e = static_cast<std::int8_t>(b[2]) % 40;  // scales 2^-39 .. 2^39
      in.v[k] = std::ldexp(static_cast<double>(m % 64), e);
    } else {
      std::memcpy(&in.v[k], b.data(), 8);
    }
  }
  return in;
}

using Q3 = std::array<mpq_class, 3>;
Q3 q3(const Vec3& v) { return {exact_of(v.x), exact_of(v.y), exact_of(v.z)}; }
Q3 minus(const Q3& a, const Q3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Q3 cross(const Q3& a, const Q3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
mpq_class dot(const Q3& a, const Q3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool zero(const Vec3& v) { return v.x == 0 && v.y == 0 && v.z == 0; }

// The format's parameters: the largest finite value, the overflow threshold (values at or beyond round to inf)
// and the next value towards ±inf.
struct Format {
  bool binary32;
  [[nodiscard]] double next(double x, double towards) const {
    return binary32 ? static_cast<double>(std::nextafter(static_cast<float>(x), static_cast<float>(towards)))
                    : std::nextafter(x, towards);
  }
  [[nodiscard]] double largest() const { return binary32 ? FLT_MAX : DBL_MAX; }
  [[nodiscard]] mpq_class overflow() const {
    return binary32 ? power_of_two(128) - power_of_two(103) : power_of_two(1024) - power_of_two(970);
  }
  [[nodiscard]] bool is_value(double x) const { return !binary32 || static_cast<double>(static_cast<float>(x)) == x; }
};

// Whether r (a finite value of the format) is q rounded to nearest, ties to even (verified by the rounding
// interval of r; the sign of a zero is free, as the contract's output says).
bool is_rn(const mpq_class& q, double r, const Format& f) {
  if (!std::isfinite(r) || !f.is_value(r)) return false;
  const mpq_class x = exact_of(r);
  const double below = f.next(r, -HUGE_VAL), above = f.next(r, HUGE_VAL);
  const mpq_class lo = std::isinf(below) ? mpq_class(x - (f.overflow() - x)) : mpq_class((x + exact_of(below)) / 2);
  const mpq_class hi = std::isinf(above) ? f.overflow() : mpq_class((x + exact_of(above)) / 2);
  if (q < lo || q > hi) return false;
  if (q == lo || q == hi) {
    const bool even = f.binary32 ? (std::bit_cast<std::uint32_t>(static_cast<float>(std::fabs(r))) & 1) == 0
                                 : (std::bit_cast<std::uint64_t>(std::fabs(r)) & 1) == 0;
    return even;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("spawn");
    raykernel::fuzz::set_input_describer(describe_current);
    return true;
  }();
  (void)initialized;
  current = decode({data, size});
  const auto& v = current.v;
  const auto vec = [&](std::size_t k) { return Vec3{v[k], v[k + 1], v[k + 2]}; };
  const bool binary32 = (current.mode & 1) != 0, to = (current.mode & 2) != 0, point = (current.mode & 4) != 0;
  const Format f{binary32};
  const raykernel::Ray ray{vec(0), vec(3)};
  const raykernel::HitPoint hit = point ? raykernel::HitPoint::at(vec(0)) : raykernel::HitPoint::crossing(ray);
  const raykernel::Triangle tri{vec(6), vec(9), vec(12)};
  const Vec3 w_or_q = vec(15);
  const raykernel::OriginFormat format = binary32 ? raykernel::OriginFormat::binary32 : raykernel::OriginFormat::binary64;

  std::optional<raykernel::SpawnedOrigin> answer;
  std::string reason;
  try {
    answer = to ? raykernel::spawn_to(hit, tri, w_or_q, format) : raykernel::spawn(hit, tri, w_or_q, format);
  } catch (const raykernel::invalid_input& e) {
    reason = e.what();
    check(!reason.empty(), "invalid_input without a reason");
  }

  // The certified fast path (spawn_certified.cpp) against the exact path alone: the same origin bit for bit, or
  // the same reason.
  {
    std::optional<raykernel::SpawnedOrigin> exact;
    std::string exact_reason;
    try {
      exact = to ? raykernel::spawn_to_exact(hit, tri, w_or_q, format) : raykernel::spawn_exact(hit, tri, w_or_q, format);
    } catch (const raykernel::invalid_input& e) {
      exact_reason = e.what();
    }
    check(reason == exact_reason, "spawn and spawn_exact give different reasons");
    check(answer.has_value() == exact.has_value(), "spawn and spawn_exact disagree on validity");
    if (answer && exact) {
      const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
      check(bits(answer->origin.x) == bits(exact->origin.x) && bits(answer->origin.y) == bits(exact->origin.y) &&
                bits(answer->origin.z) == bits(exact->origin.z) && answer->steps == exact->steps,
            "spawn and spawn_exact give different origins");
    }
  }

  // The oracle.
  const bool finite_input = (point ? finite(vec(0)) : finite(ray.origin) && finite(ray.direction)) && finite(tri.a) &&
                            finite(tri.b) && finite(tri.c) && finite(w_or_q);
  if (!finite_input) {
    check(!answer, "a non-finite input was answered");
    return 0;
  }
  if ((!point && zero(ray.direction)) || (!to && zero(w_or_q))) {
    check(!answer, "a zero direction was answered");
    return 0;
  }
  const Q3 a = q3(tri.a);
  const Q3 n = cross(minus(q3(tri.b), a), minus(q3(tri.c), a));
  if (sgn(n[0]) == 0 && sgn(n[1]) == 0 && sgn(n[2]) == 0) {
    check(!answer, "a degenerate triangle was answered");
    return 0;
  }
  Q3 p;
  if (point) {
    p = q3(vec(0));
  } else {
    const Q3 o = q3(ray.origin), d = q3(ray.direction);
    const mpq_class den = dot(d, n);
    if (sgn(den) == 0) {
      check(!answer, "a ray parallel to the plane was answered");
      return 0;
    }
    const mpq_class t = dot(minus(a, o), n) / den;
    p = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]};
  }
  const int s = to ? sgn(dot(minus(q3(w_or_q), a), n)) : sgn(dot(q3(w_or_q), n));
  if (s == 0) {
    check(!answer, "w parallel to the plane (or q on it) was answered");
    return 0;
  }
  bool overflows = false;
  for (const mpq_class& c : p) overflows = overflows || abs(c) >= f.overflow();
  if (overflows) {
    check(!answer, "a P-hat beyond the format was answered");
    return 0;
  }
  if (!answer) {
    // The one reason left: no value of the format on side s along the axis. Then the threshold lies at or
    // beyond the largest finite value in the direction of the steps.
    check(reason.find("no origin") != std::string::npos, "a valid query was refused: " + reason);
    return 0;
  }

  const raykernel::SpawnedOrigin& o = *answer;
  const double oc[3] = {o.origin.x, o.origin.y, o.origin.z};
  const Q3 oq = q3(o.origin);
  check(sgn(dot(minus(oq, a), n)) == s, "the origin is not strictly on side s");
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (abs(n[static_cast<std::size_t>(k)]) > abs(n[static_cast<std::size_t>(axis)])) axis = k;
  const int delta = sgn(n[static_cast<std::size_t>(axis)]) * s;
  for (int k = 0; k < 3; ++k) {
    if (k == axis && o.steps != 0) continue;
    check(is_rn(p[static_cast<std::size_t>(k)], oc[k], f), "coordinate " + std::to_string(k) + " is not P rounded to nearest");
  }
  if (o.steps != 0) {
    // One step back is not on side s (k minimal); walking back k steps reaches RN(P_i) (k exact), checked for
    // small k by stepping and for large k by the ordinal difference.
    Vec3 back = o.origin;
    double* b = &back.x;
    b[axis] = f.next(b[axis], delta > 0 ? -HUGE_VAL : HUGE_VAL);
    if (b[axis] == 0) b[axis] = 0;
    check(sgn(dot(minus(q3(back), a), n)) != s, "one step back is already on side s: k is not the smallest");
    const auto ordinal = [&](double x) -> std::int64_t {
      if (binary32) {
        const auto u = std::bit_cast<std::uint32_t>(static_cast<float>(x));
        const std::int64_t m = u & 0x7fffffffu;
        return (u >> 31) != 0 ? -m : m;
      }
      const auto u = std::bit_cast<std::uint64_t>(x);
      const auto m = static_cast<std::int64_t>(u & 0x7fffffffffffffffu);
      return (u >> 63) != 0 ? -m : m;
    };
    const std::int64_t end = ordinal(oc[axis]);
    // start = end ∓ k in two's complement (k may exceed 2^63; the true start is an ordinal, so it fits).
    const auto u_end = static_cast<std::uint64_t>(end);
    const auto start = static_cast<std::int64_t>(delta > 0 ? u_end - o.steps : u_end + o.steps);
    const std::uint64_t magnitude = start < 0 ? 0 - static_cast<std::uint64_t>(start) : static_cast<std::uint64_t>(start);
    double rounded;
    if (binary32) {
      const float m = std::bit_cast<float>(static_cast<std::uint32_t>(magnitude));
      rounded = start < 0 ? -static_cast<double>(m) : static_cast<double>(m);
    } else {
      const double m = std::bit_cast<double>(magnitude);
      rounded = start < 0 ? -m : m;
    }
    check(is_rn(p[static_cast<std::size_t>(axis)], rounded, f), "the origin is not k steps from P rounded to nearest");
    // And P̂ itself is not on side s.
    Vec3 hat = o.origin;
    (&hat.x)[axis] = rounded;
    check(sgn(dot(minus(q3(hat), a), n)) != s, "k >= 1 although P-hat is on side s");
  }
  return 0;
}
