// Generated nearest-hit scenes for tests: one ray and several planes, mixing random planes with planes
// whose exact t tie (through a common point of the ray, duplicated, coincident with another
// representation) or nearly tie (moved by a few ulps), and planes that are never hit (parallel, in-plane,
// behind). Exact properties hold by construction: the ray and every constructed coordinate are short
// dyadic numbers, so the sums the constructions need are exact, and each construction checks it in
// rationals before promising anything. The tests use an exact oracle (oracle.hpp), not these promises,
// for the expected answers; `kinds` only says what a scene contains (for RC_CLASSIFY and messages).
#pragma once

#include "support/oracle.hpp"

#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>

#include <gmpxx.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::test_support {

struct PlaneScene {
  Ray ray;
  std::vector<Plane> planes;
  std::vector<std::string> kinds;  // how each plane was made
};

class SceneDraw {
 public:
  explicit SceneDraw(const testkit::BitSource& bits) : bits_(bits) {}

  std::uint64_t word() { return bits_(); }
  int integer(int lo, int hi) {
    return lo + static_cast<int>(word() % static_cast<std::uint64_t>(static_cast<std::int64_t>(hi) - lo + 1));
  }
  // A short dyadic: an integer of at most 20 bits times 2^e, e in [−6, 2].
  double short_dyadic() { return std::ldexp(integer(-(1 << 20), 1 << 20), integer(-6, 2)); }
  // A full-precision value in [−4, 4].
  double full() { return static_cast<double>(static_cast<std::int64_t>(word() >> 10) - (std::int64_t{1} << 53)) * 0x1p-51; }
  Vec3 short_vector() { return {short_dyadic(), short_dyadic(), short_dyadic()}; }
  Vec3 full_vector() { return {full(), full(), full()}; }
  Vec3 small_integer_vector(int limit) {
    return {static_cast<double>(integer(-limit, limit)), static_cast<double>(integer(-limit, limit)),
            static_cast<double>(integer(-limit, limit))};
  }

 private:
  const testkit::BitSource& bits_;
};

inline bool is_zero(const Vec3& v) { return v.x == 0 && v.y == 0 && v.z == 0; }
inline Vec3 nonzero(Vec3 v) {
  if (is_zero(v)) v.y = 1;
  return v;
}

// a + s·b if every component is exact in binary64.
inline std::optional<Vec3> exact_point_along(const Vec3& a, double s, const Vec3& b) {
  const Vec3 r{a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
  const bool exact = mpq_class(r.x) == mpq_class(a.x) + mpq_class(s) * mpq_class(b.x) &&
                     mpq_class(r.y) == mpq_class(a.y) + mpq_class(s) * mpq_class(b.y) &&
                     mpq_class(r.z) == mpq_class(a.z) + mpq_class(s) * mpq_class(b.z);
  if (!exact || !std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z)) return std::nullopt;
  return r;
}

// A scene of 1 to `max_planes` planes along one ray (see the file comment).
inline PlaneScene make_plane_scene(const testkit::BitSource& bits, int max_planes = 8) {
  SceneDraw draw(bits);
  PlaneScene scene;
  scene.ray = {draw.short_vector(), nonzero(draw.short_vector())};
  const Ray& r = scene.ray;
  // The pivot: a point of the ray at s > 0 (a dyadic with few bits), through which "pivot" planes pass.
  const double s = std::ldexp(draw.integer(1, 1 << 10), draw.integer(-10, 0));
  const std::optional<Vec3> pivot = exact_point_along(r.origin, s, r.direction);
  const int count = draw.integer(1, max_planes);
  while (static_cast<int>(scene.planes.size()) < count) {
    const int kind = draw.integer(0, 9);
    const bool have_earlier = !scene.planes.empty();
    switch (kind) {
      case 0:  // random, full precision
        scene.planes.push_back({draw.full_vector(), nonzero(draw.full_vector())});
        scene.kinds.push_back("random");
        break;
      case 1:
      case 2:  // through the pivot with a random normal: every such plane has t = s exactly
        if (!pivot) continue;
        scene.planes.push_back({*pivot, nonzero(draw.full_vector())});
        scene.kinds.push_back("pivot");
        break;
      case 3: {  // through the pivot moved by a few ulps in one coordinate: t within ~ulps of s
        if (!pivot) continue;
        Vec3 p = *pivot;
        double& c = draw.integer(0, 2) == 0 ? p.x : (draw.integer(0, 1) == 0 ? p.y : p.z);
        for (int k = draw.integer(1, 3); k > 0; --k) c = std::nextafter(c, draw.integer(0, 1) ? HUGE_VAL : -HUGE_VAL);
        scene.planes.push_back({p, nonzero(draw.full_vector())});
        scene.kinds.push_back("near-pivot");
        break;
      }
      case 4:  // a duplicate of an earlier plane (the same doubles)
        if (!have_earlier) continue;
        scene.planes.push_back(scene.planes[static_cast<std::size_t>(draw.integer(0, static_cast<int>(scene.planes.size()) - 1))]);
        scene.kinds.push_back("duplicate");
        break;
      case 5: {  // a plane with a small integer normal and its coincident twin: normal ×3, point moved within the plane
        const Vec3 n = nonzero(draw.small_integer_vector(16));
        const Vec3 p = draw.short_vector();
        const Vec3 w = draw.small_integer_vector(8);
        const Vec3 along{n.y * w.z - n.z * w.y, n.z * w.x - n.x * w.z, n.x * w.y - n.y * w.x};  // exact: small integers
        const std::optional<Vec3> q = exact_point_along(p, std::ldexp(1.0, draw.integer(-4, 4)), along);
        if (!q) continue;
        scene.planes.push_back({p, n});
        scene.kinds.push_back("coincident base");
        scene.planes.push_back({*q, {3 * n.x, 3 * n.y, 3 * n.z}});
        scene.kinds.push_back("coincident twin");
        break;
      }
      case 6: {  // an earlier plane moved by a few ulps along one coordinate of its point: a near tie
        if (!have_earlier) continue;
        Plane p = scene.planes[static_cast<std::size_t>(draw.integer(0, static_cast<int>(scene.planes.size()) - 1))];
        double& c = draw.integer(0, 2) == 0 ? p.point.x : (draw.integer(0, 1) == 0 ? p.point.y : p.point.z);
        c = std::nextafter(c, draw.integer(0, 1) ? HUGE_VAL : -HUGE_VAL);
        scene.planes.push_back(p);
        scene.kinds.push_back("offset");
        break;
      }
      case 7: {  // parallel to the ray (d·n = 0 exactly) or containing it
        const Vec3& d = r.direction;
        const Vec3 w = draw.small_integer_vector(8);
        const Vec3 n{d.y * w.z - d.z * w.y, d.z * w.x - d.x * w.z, d.x * w.y - d.y * w.x};
        const bool exact = mpq_class(n.x) == mpq_class(d.y) * w.z - mpq_class(d.z) * w.y &&
                           mpq_class(n.y) == mpq_class(d.z) * w.x - mpq_class(d.x) * w.z &&
                           mpq_class(n.z) == mpq_class(d.x) * w.y - mpq_class(d.y) * w.x;
        if (!exact || is_zero(n)) continue;
        const bool in_plane = draw.integer(0, 1) == 0;
        scene.planes.push_back({in_plane ? r.origin : draw.short_vector(), n});
        scene.kinds.push_back(in_plane ? "in-plane" : "parallel");
        break;
      }
      case 8: {  // behind the origin: through o − s'·d
        const std::optional<Vec3> b = exact_point_along(r.origin, -std::ldexp(1.0, draw.integer(-3, 3)), r.direction);
        if (!b) continue;
        scene.planes.push_back({*b, nonzero(draw.full_vector())});
        scene.kinds.push_back("behind");
        break;
      }
      default: {  // the plane of a hard query (near-parallel, subnormal, huge, ...), with this ray
        const testkit::QueryKind qk =
            testkit::all_query_kinds[static_cast<std::size_t>(draw.integer(0, testkit::query_kind_count - 1))];
        scene.planes.push_back(testkit::make_query(qk, bits).plane);
        scene.kinds.push_back(std::string("hard: ") + std::string(testkit::to_string(qk)));
        break;
      }
    }
  }
  while (static_cast<int>(scene.planes.size()) > count) {  // a coincident pair may overshoot by one
    scene.planes.pop_back();
    scene.kinds.pop_back();
  }
  return scene;
}

// The nearest hit by brute force in exact rationals (GMP) with the integer-division rounding of oracle.hpp:
// no code shared with the kernel.
struct OracleNearest {
  std::optional<std::size_t> plane;
  mpq_class t;
  [[nodiscard]] double rounded_t() const { return round_by_integer_division(t); }
};
inline OracleNearest brute_force_nearest(const Ray& ray, const std::vector<Plane>& planes) {
  OracleNearest best;
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const ExactTerms e = exact_terms(ray, planes[k]);
    if (e.den == 0) continue;
    const mpq_class t = e.num / e.den;
    if (t < 0) continue;
    if (!best.plane || t < best.t) {
      best.plane = k;
      best.t = t;
    }
  }
  return best;
}

inline std::string describe_scene(const PlaneScene& s) {
  auto v = [](const Vec3& a) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "(%a, %a, %a)", a.x, a.y, a.z);
    return std::string(buf);
  };
  std::string out = "ray o=" + v(s.ray.origin) + " d=" + v(s.ray.direction) + "\n";
  for (std::size_t k = 0; k < s.planes.size(); ++k)
    out += "  plane " + std::to_string(k) + " [" + s.kinds[k] + "] p=" + v(s.planes[k].point) + " n=" + v(s.planes[k].normal) + "\n";
  return out;
}

}  // namespace raykernel::test_support
