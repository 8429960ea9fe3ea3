// fuzz_sphere: one ray–sphere query per input (docs/contract.md §10), answered by raykernel's certified path
// (`intersect_traced`, `relation`) and its exact reference (`intersect_exact`, `intersect_exact_rational`), and
// checked against an oracle that shares no code with either: GMP rationals from the definitions (A, B, C, D, U,
// V), each root verified as the rounding to nearest-even of U ∓ √V by exact comparisons with the midpoints beside
// it (the sign of U − m ∓ √V read from U − m and (U − m)² − V), and CGAL's Ray_3/Sphere_3 do_intersect (a ball:
// where the origin is outside, the ray meets it exactly when a root is ≥ 0).
//
// Input: byte 0 selects the decoder. < 0x40: 10 raw doubles (every bit pattern); 0x40–0x7f: 10 small integers
// times powers of two (2 bytes of integer, 1 of exponent each), where tangents, origins on the surface and ties
// are common; ≥ 0x80: a hard query of kind (byte 0 − 0x80) mod 12 of raykernel::testkit::make_sphere_query, its
// words drawn from the bytes that follow.
//
// Checked for every input: `validate` rejects exactly the inputs with a non-finite component, a zero direction or
// a radius that is not positive (decided here from the bits), and then every entry point throws invalid_input
// with validate's reason; for valid input certified == exact bit for bit, `relation` agrees, the origin and
// relation are the signs of the oracle's C and D, U and V are the oracle's, every root is verified, and CGAL
// agrees where its ball semantics and §10's surface agree (origin outside); and a set of nine spheres derived from
// the query (its BVH) gives nearest_hit_exact's answer, with and without an interval.
#include "fuzz_exact.hpp"
#include "fuzz_support.hpp"

#include <raykernel/sphere.hpp>
#include <raykernel/testkit/sphere_queries.hpp>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
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
#include <vector>

namespace {

using raykernel::Ray;
using raykernel::Sphere;
using raykernel::SphereIntersection;
using raykernel::SphereOrigin;
using raykernel::SphereRelation;
using raykernel::Vec3;
using raykernel::fuzz::bits;
using raykernel::fuzz::check;
using raykernel::fuzz::exact_of;
using raykernel::fuzz::power_of_two;
using K = CGAL::Exact_predicates_exact_constructions_kernel;

struct Input {
  std::uint8_t mode = 0;
  Ray ray{};
  Sphere sphere{};
};
Input current;

std::string describe_current() {
  std::string s = "mode ";
  s += std::to_string(current.mode);
  s += ':';
  for (double x : {current.ray.origin.x, current.ray.origin.y, current.ray.origin.z, current.ray.direction.x,
                   current.ray.direction.y, current.ray.direction.z, current.sphere.center.x, current.sphere.center.y,
                   current.sphere.center.z, current.sphere.radius}) {
    s += ' ';
    s += raykernel::fuzz::hex(x);
  }
  return s;
}

Input decode(std::span<const std::uint8_t> bytes) {
  Input in;
  if (bytes.empty()) return in;
  in.mode = bytes[0];
  bytes = bytes.subspan(1);
  if (in.mode >= 0x80) {
    std::size_t at = 0;
    const raykernel::testkit::BitSource words = [&]() {
      std::uint64_t w = 0;
      for (int j = 0; j < 8; ++j, ++at) w |= static_cast<std::uint64_t>(at < bytes.size() ? bytes[at] : 0) << (8 * j);
      return w;
    };
    const auto kind = raykernel::testkit::all_sphere_query_kinds[(in.mode - 0x80) % raykernel::testkit::sphere_query_kind_count];
    const raykernel::testkit::SphereQuery q = raykernel::testkit::make_sphere_query(kind, words);
    in.ray = q.ray;
    in.sphere = q.sphere;
    return in;
  }
  const bool structured = in.mode >= 0x40;
  const std::size_t width = structured ? 3 : 8;
  std::array<double, 10> v{};
  for (std::size_t k = 0; k < v.size(); ++k) {
    std::array<std::uint8_t, 8> b{};
    for (std::size_t j = 0; j < width; ++j) {
      const std::size_t at = k * width + j;
      b[j] = at < bytes.size() ? bytes[at] : 0;
    }
    if (structured) {
      const auto m = static_cast<std::int16_t>(b[0] | (b[1] << 8));
      const int e = static_cast<std::int8_t>(b[2]) % 40;  // scales 2^-39 .. 2^39
      v[k] = std::ldexp(static_cast<double>(m % 64), e);
    } else {
      std::memcpy(&v[k], b.data(), 8);
    }
  }
  in.ray = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
  in.sphere = {{v[6], v[7], v[8]}, v[9]};
  return in;
}

bool finite_by_bits(const Vec3& v) { return raykernel::fuzz::finite_vector_by_bits(v); }
bool invalid_by_bits(const Ray& r, const Sphere& s) {
  const bool radius_ok = raykernel::fuzz::finite_by_bits(s.radius) && (bits(s.radius) >> 63) == 0 &&
                         !raykernel::fuzz::zero_by_bits(s.radius);
  return raykernel::fuzz::ray_invalid_by_bits(r) || !finite_by_bits(s.center) || !radius_ok;
}

// sign(t − m) for t = U + s·√V (s = ±1, V ≥ 0), exactly: with w = U − m, t − m = w + s·√V.
int side(const mpq_class& u, const mpq_class& v, int s, const mpq_class& m) {
  const mpq_class w = u - m;
  const int sw = sgn(w);
  if (s > 0) {
    if (sw >= 0) return (sw > 0 || sgn(v) > 0) ? 1 : 0;
    return sgn(mpq_class(v - w * w));  // √V against −w > 0
  }
  if (sw <= 0) return (sw < 0 || sgn(v) > 0) ? -1 : 0;
  return sgn(mpq_class(w * w - v));  // w > 0 against √V
}

// Whether r is the root U + s·√V rounded to nearest, ties to even, with gradual underflow (the sign kept),
// overflow to ±inf and an exact zero as +0: from the sides of the root at the ends of r's rounding interval.
bool is_rounded_root(const mpq_class& u, const mpq_class& v, int s, double r) {
  if (std::isnan(r)) return false;
  const int s0 = side(u, v, s, 0);
  if (s0 == 0) return bits(r) == 0;
  if (std::signbit(r) != (s0 < 0)) return false;
  // sign(|t| − a) for a ≥ 0.
  auto side_abs = [&](const mpq_class& a) { return s0 > 0 ? side(u, v, s, a) : -side(u, v, s, mpq_class(-a)); };
  const mpq_class overflow = power_of_two(1024) - power_of_two(970);
  const double m = std::fabs(r);
  if (std::isinf(m)) return side_abs(overflow) >= 0;
  const mpq_class mq = exact_of(m);
  const mpq_class hi = m == DBL_MAX ? overflow : mpq_class((mq + exact_of(std::nextafter(m, HUGE_VAL))) / 2);
  const mpq_class lo = m == 0 ? mpq_class(0) : mpq_class((mq + exact_of(std::nextafter(m, 0.0))) / 2);
  const int above = side_abs(hi), below = side_abs(lo);
  const bool even = (bits(m) & 1) == 0;
  if (above > 0 || below < 0) return false;
  return !((above == 0 || below == 0) && !even);
}

std::string text(const SphereIntersection& a) {
  return std::string(to_string(a.origin)) + " " + std::string(to_string(a.relation)) + " " +
         raykernel::fuzz::hex(a.t1) + " " + raykernel::fuzz::hex(a.t2);
}

mpq_class rational_of(const raykernel::Rational& r) {
  mpq_class q(mpz_class(r.numerator), mpz_class(r.denominator));
  q.canonicalize();
  return q;
}


}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("sphere");
    raykernel::fuzz::set_input_describer(describe_current);
    return true;
  }();
  (void)initialized;
  current = decode({data, size});
  const Ray& ray = current.ray;
  const Sphere& sphere = current.sphere;

  const std::optional<std::string> reason = raykernel::validate(ray, sphere);
  check(reason.has_value() == invalid_by_bits(ray, sphere), [&] {
    return "validate says " + reason.value_or("valid") + ", the bits say " + (invalid_by_bits(ray, sphere) ? "invalid" : "valid");
  });
  if (reason) {
    for (int entry = 0; entry < 4; ++entry) {
      std::string thrown;
      try {
        switch (entry) {
          case 0: (void)raykernel::intersect(ray, sphere); break;
          case 1: (void)raykernel::relation(ray, sphere); break;
          case 2: (void)raykernel::intersect_exact(ray, sphere); break;
          default: (void)raykernel::intersect_exact_rational(ray, sphere); break;
        }
      } catch (const raykernel::invalid_input& e) {
        thrown = e.what();
      }
      check(thrown == *reason, [&] { return "entry point " + std::to_string(entry) + " threw '" + thrown + "'"; });
    }
    return 0;
  }

  const raykernel::TracedSphereIntersection traced = raykernel::intersect_traced(ray, sphere);
  const SphereIntersection certified = traced.intersection, exact = raykernel::intersect_exact(ray, sphere);
  check(text(certified) == text(exact), [&] { return "certified " + text(certified) + ", exact " + text(exact); });
  const raykernel::SphereClassification c = raykernel::relation(ray, sphere);
  check(c.origin == exact.origin && c.relation == exact.relation, "relation differs from intersect_exact");

  // The oracle, from the definitions.
  const mpq_class ox = exact_of(ray.origin.x), oy = exact_of(ray.origin.y), oz = exact_of(ray.origin.z);
  const mpq_class dx = exact_of(ray.direction.x), dy = exact_of(ray.direction.y), dz = exact_of(ray.direction.z);
  const mpq_class fx = ox - exact_of(sphere.center.x), fy = oy - exact_of(sphere.center.y),
                  fz = oz - exact_of(sphere.center.z), r = exact_of(sphere.radius);
  const mpq_class a = dx * dx + dy * dy + dz * dz, b = dx * fx + dy * fy + dz * fz;
  const mpq_class cc = fx * fx + fy * fy + fz * fz - r * r, d = b * b - a * cc;
  const SphereOrigin origin = sgn(cc) < 0 ? SphereOrigin::inside : sgn(cc) == 0 ? SphereOrigin::on_surface : SphereOrigin::outside;
  const SphereRelation relation = sgn(d) < 0 ? SphereRelation::miss : sgn(d) == 0 ? SphereRelation::tangent : SphereRelation::cross;
  check(exact.origin == origin && exact.relation == relation, [&] { return "oracle: " + std::string(to_string(origin)) + " " + std::string(to_string(relation)) + ", got " + text(exact); });
  const raykernel::ExactSphereIntersection rational = raykernel::intersect_exact_rational(ray, sphere);
  check(rational.relation == relation && rational.origin == origin, "intersect_exact_rational's classification");
  if (relation == SphereRelation::miss) {
    check(std::isnan(exact.t1) && std::isnan(exact.t2) && !rational.u && !rational.v, "a miss has no roots");
  } else {
    const mpq_class u = -b / a, v = d / (a * a);
    check(rational.u && rational.v && rational_of(*rational.u) == u && rational_of(*rational.v) == v,
          [&] { return "U V: got " + (rational.u ? rational.u->str() : "-") + " " + (rational.v ? rational.v->str() : "-"); });
    check(is_rounded_root(u, v, -1, exact.t1), [&] { return "t1 is not RN(U − √V): " + raykernel::fuzz::hex(exact.t1); });
    check(is_rounded_root(u, v, +1, exact.t2), [&] { return "t2 is not RN(U + √V): " + raykernel::fuzz::hex(exact.t2); });
  }

  // A set of nine through its BVH (SphereSet::bvh, from 8 spheres on): the sphere, copies moved along the ray by
  // multiples of r (touching, ties) and nudged by ulps, against the exact reference, with and without an interval.
  std::vector<Sphere> set_spheres{sphere};
  for (int k = 1; k < 9; ++k) {
    Sphere s = sphere;
    const double step = (k % 4) * sphere.radius;
    s.center = {sphere.center.x + step * ray.direction.x, sphere.center.y + step * ray.direction.y,
                sphere.center.z + step * ray.direction.z};
    if (k >= 4) s.radius = std::nextafter(s.radius, k % 2 ? 0.0 : DBL_MAX);
    if (!(s.radius > 0) || raykernel::validate(s)) continue;
    set_spheres.push_back(s);
  }
  const raykernel::SphereSet set(set_spheres);
  for (const raykernel::RayInterval interval :
       {raykernel::RayInterval{}, raykernel::RayInterval{0, std::isfinite(exact.t1) && exact.t1 > 0 ? exact.t1 : 1.0}}) {
    const std::optional<raykernel::SphereHit> hit = raykernel::nearest_hit(ray, interval, set);
    const std::optional<raykernel::SphereHit> want = raykernel::nearest_hit_exact(ray, interval, set_spheres);
    check(hit.has_value() == want.has_value() && (!hit || (hit->sphere == want->sphere &&
                                                           std::bit_cast<std::uint64_t>(hit->t) ==
                                                               std::bit_cast<std::uint64_t>(want->t))),
          [&] { return std::string("sphere set (") + (set.bvh() ? "bvh" : "list") + "): nearest_hit differs from nearest_hit_exact"; });
    check(raykernel::occluded(ray, interval, set) == want.has_value(), "sphere set: occluded differs from the exact hit");
  }

  // CGAL's ball: for an origin outside, the ray meets it exactly when the larger root is ≥ 0.
  if (origin == SphereOrigin::outside) {
    const K::Point_3 o(ray.origin.x, ray.origin.y, ray.origin.z), centre(sphere.center.x, sphere.center.y, sphere.center.z);
    const K::Vector_3 dir(ray.direction.x, ray.direction.y, ray.direction.z);
    const K::FT radius(sphere.radius);
    const bool cgal = CGAL::do_intersect(K::Ray_3(o, dir), K::Sphere_3(centre, radius * radius));
    const bool ours = relation != SphereRelation::miss && side(-b / a, d / (a * a), +1, 0) >= 0;
    check(cgal == ours, [&] { return std::string("CGAL do_intersect says ") + (cgal ? "meets" : "misses"); });
  }
  return 0;
}
