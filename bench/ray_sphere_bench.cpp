// The ray–sphere benchmarks (docs/contract.md §10), measured in the same run as the others:
//
//   sphere/<path>/<workload>
//     path:     naive       the textbook quadratic in doubles (intersect_naive: origin, relation, both roots)
//               interval    pbrt-v4's way (src/pbrt/shapes.h, Sphere::BasicIntersect): the quadratic in interval
//                           arithmetic with outward rounding after every operation (pbrt's Interval, rounded
//                           by one ulp outward), a miss whenever the discriminant's interval reaches below 0,
//                           the roots as the midpoints of their intervals: no guarantee either way
//               certified   intersect: origin, relation, both roots correctly rounded
//               relation    origin and relation (nothing rounded)
//               exact       intersect_exact (GMP rationals, MPFR)
//     workload: random      4096 queries (components uniform in [-1, 1], radius in (0, 1]), in L2
//               degenerate  4096 queries: exact tangents and an ulp off, origins on the surface and an ulp off,
//                           rounding ties, far-away spheres where C cancels (raykernel::testkit)
//
// Items per second count queries. The buffers are generated before timing and checked once (certified ==
// exact). The certified benchmarks report the fraction each stage decided (rel_*, roots_*) and
// exact_per_million. Registered at load time: main is ray_plane_bench.cpp's.
#include <raykernel/fp_environment.hpp>
#include <raykernel/sphere.hpp>
#include <raykernel/testkit/sphere_queries.hpp>

#include <benchmark/benchmark.h>

#include "rotate.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace raykernel::bench {
namespace {

using testkit::SphereQuery;
using testkit::SphereQueryKind;

constexpr std::size_t l2_size = 4096;

std::vector<SphereQuery> generate(std::initializer_list<SphereQueryKind> kinds, std::uint64_t seed) {
  return hard_query_buffer(kinds, seed, l2_size, testkit::make_sphere_query);
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b); }

void check(const std::vector<SphereQuery>& queries, const char* name) {
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const SphereIntersection a = intersect(queries[i].ray, queries[i].sphere);
    const SphereIntersection b = intersect_exact(queries[i].ray, queries[i].sphere);
    if (a.origin != b.origin || a.relation != b.relation || !same(a.t1, b.t1) || !same(a.t2, b.t2)) {
      std::fprintf(stderr, "raykernel_bench: certified != exact on sphere workload %s, query %zu\n", name, i);
      std::abort();
    }
  }
}

const std::vector<SphereQuery>& random_workload() {
  static const std::vector<SphereQuery> w = [] {
    auto q = generate({SphereQueryKind::random}, 29);
    check(q, "random");
    return q;
  }();
  return w;
}

const std::vector<SphereQuery>& degenerate_workload() {
  static const std::vector<SphereQuery> w = [] {
    auto q = generate({SphereQueryKind::tangent, SphereQueryKind::near_tangent, SphereQueryKind::on_surface,
                       SphereQueryKind::near_surface, SphereQueryKind::rounding_tie, SphereQueryKind::far_cancel},
                      30);
    check(q, "degenerate");
    return q;
  }();
  return w;
}

// pbrt-v4's Interval in miniature: each operation rounded to nearest, then widened by one ulp outward (pbrt
// rounds with NextFloatDown/NextFloatUp of the rounded results).
struct Interval {
  double lo, hi;
};
Interval widen(double lo, double hi) { return {std::nextafter(lo, -INFINITY), std::nextafter(hi, INFINITY)}; }
Interval exact(double x) { return {x, x}; }
Interval operator+(Interval a, Interval b) { return widen(a.lo + b.lo, a.hi + b.hi); }
Interval operator-(Interval a, Interval b) { return widen(a.lo - b.hi, a.hi - b.lo); }
Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return widen(std::fmin(std::fmin(p[0], p[1]), std::fmin(p[2], p[3])),
               std::fmax(std::fmax(p[0], p[1]), std::fmax(p[2], p[3])));
}
Interval square(Interval a) {
  if (a.lo >= 0) return widen(a.lo * a.lo, a.hi * a.hi);
  if (a.hi <= 0) return widen(a.hi * a.hi, a.lo * a.lo);
  return widen(0, std::fmax(a.lo * a.lo, a.hi * a.hi));
}

struct IntervalAnswer {
  bool hit;
  double t0, t1;
};

// Sphere::BasicIntersect's arithmetic on the ray's origin relative to the centre: a = |d|², b = 2(d·f),
// c = |f|² − r², discrim = b² − 4ac; a miss when discrim's lower bound is below 0; q = −(b ± √discrim)/2, roots
// q/a and c/q (the stable form), reported as their intervals' midpoints.
IntervalAnswer interval_intersect(const SphereQuery& q) {
  const Interval fx = exact(q.ray.origin.x) - exact(q.sphere.center.x), fy = exact(q.ray.origin.y) - exact(q.sphere.center.y),
                 fz = exact(q.ray.origin.z) - exact(q.sphere.center.z);
  const Interval dx = exact(q.ray.direction.x), dy = exact(q.ray.direction.y), dz = exact(q.ray.direction.z);
  const Interval a = square(dx) + square(dy) + square(dz);
  const Interval b = exact(2) * (dx * fx + dy * fy + dz * fz);
  const Interval c = square(fx) + square(fy) + square(fz) - square(exact(q.sphere.radius));
  const Interval discrim = square(b) - exact(4) * a * c;
  if (discrim.lo < 0) return {false, 0, 0};
  const Interval root{std::nextafter(std::sqrt(discrim.lo), -INFINITY), std::nextafter(std::sqrt(discrim.hi), INFINITY)};
  const Interval qv = b.lo < 0 ? exact(-0.5) * (b - root) : exact(-0.5) * (b + root);
  const double t0 = 0.5 * (qv.lo / a.hi + qv.hi / a.lo), t1 = 0.5 * (c.lo / qv.hi + c.hi / qv.lo);
  return {true, std::fmin(t0, t1), std::fmax(t0, t1)};
}

void add_stage_counters(benchmark::State& state, const std::vector<SphereQuery>& queries) {
  std::array<double, 4> relation{}, rounding{};
  double with_roots = 0, interval_wrong = 0;
  for (const SphereQuery& q : queries) {
    const TracedSphereIntersection r = intersect_traced(q.ray, q.sphere);
    relation[static_cast<std::size_t>(r.relation_stage)] += 1;
    if (r.intersection.relation != SphereRelation::miss) {
      rounding[static_cast<std::size_t>(r.rounding_stage)] += 1;
      with_roots += 1;
    }
    interval_wrong += interval_intersect(q).hit != (r.intersection.relation != SphereRelation::miss);
  }
  const double n = static_cast<double>(queries.size());
  const char* names[4] = {"filter", "compensated", "expansion", "exact"};
  for (std::size_t s = 2; s < 4; ++s) {
    state.counters[std::string("rel_") + names[s]] = relation[s] / n;
    state.counters[std::string("roots_") + names[s]] = with_roots > 0 ? rounding[s] / with_roots : 0;
  }
  state.counters["exact_per_million"] = 1e6 * (relation[3] + rounding[3]) / n;
  state.counters["interval_wrong_hit"] = interval_wrong / n;  // pbrt-style misses (or hits) the exact relation denies
}

void register_workload(const char* workload, const std::vector<SphereQuery>& (*queries)()) {
  auto name = [workload](const char* path) { return std::string("sphere/") + path + "/" + workload; };
  benchmark::RegisterBenchmark(name("naive").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const SphereQuery& q) { return intersect_naive(q.ray, q.sphere); });
  });
  benchmark::RegisterBenchmark(name("interval").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const SphereQuery& q) { return interval_intersect(q); });
  });
  benchmark::RegisterBenchmark(name("certified").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const SphereQuery& q) { return intersect(q.ray, q.sphere); });
    add_stage_counters(s, queries());
  });
  benchmark::RegisterBenchmark(name("relation").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const SphereQuery& q) { return relation(q.ray, q.sphere); });
  });
  // The same calls inside one DefaultFpEnvironment scope (as the plane's and the triangle's *_scoped): the
  // per-call check of the caller's floating-point environment (stmxcsr, ldmxcsr) hoisted out.
  benchmark::RegisterBenchmark(name("certified_scoped").c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, queries(), [](const SphereQuery& q) { return intersect(q.ray, q.sphere); });
  });
  benchmark::RegisterBenchmark(name("relation_scoped").c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, queries(), [](const SphereQuery& q) { return relation(q.ray, q.sphere); });
  });
  benchmark::RegisterBenchmark(name("exact").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const SphereQuery& q) { return intersect_exact(q.ray, q.sphere); });
  });
}

const bool registered = [] {
  register_workload("random", &random_workload);
  register_workload("degenerate", &degenerate_workload);
  return true;
}();

}  // namespace
}  // namespace raykernel::bench
