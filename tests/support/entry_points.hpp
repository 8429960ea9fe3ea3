// Every public entry point of the library on a list of queries (ray–plane queries, and ray–triangle queries for
// the triangle entry points), reduced to text: the answers bit for bit
// (t as its bit pattern, exact rationals as strings, exceptions as their messages). Two runs of
// `answers_of_every_entry_point` over the same queries, one in the default floating-point environment and
// one in another, must give the same text: that is the library's promise that its answers do not depend
// on the caller's rounding mode, flush-to-zero, denormals-are-zero or trap masks.
//
// Used by tests/fp_environment_test.cpp (each mode set by hand) and tests/fast_math_program.cpp (built
// with -ffast-math, so its start-up code sets FTZ and DAZ). Written to be compiled with -ffast-math too: it
// never compares or tests doubles, it only calls the library and prints bits.
#pragma once

#include <raykernel/batch.hpp>
#include <raykernel/camera.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>
#include <raykernel/testkit/plane_queries.hpp>
#include <raykernel/testkit/plane_reference_check.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/testkit/triangle_reference_check.hpp>
#include <raykernel/transform.hpp>
#include <raykernel/triangle.hpp>

#include <bit>
#include <cfenv>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace raykernel::test_support {

// The whole floating-point environment a call must leave as it found it: MXCSR on x86-64 (control bits
// and sticky flags), else the rounding mode and the raised flags.
inline std::uint64_t environment_word() {
#if defined(__x86_64__)
  return _mm_getcsr();
#else
  return static_cast<std::uint64_t>(std::fegetround()) << 32 | static_cast<std::uint64_t>(std::fetestexcept(FE_ALL_EXCEPT));
#endif
}

inline std::string bits_of(double x) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(x)));
  return buf;
}
inline std::string text_of(const Intersection& a) {
  // t's bits only where the contract defines t (any NaN is the same answer for parallel and in-plane).
  const bool has_t = a.relation == Relation::hit || a.relation == Relation::behind;
  std::string s(to_string(a.relation));
  if (has_t) s.append(" ").append(bits_of(a.t));
  return s;
}
inline std::string text_of(const std::optional<NearestHit>& h) {
  return h ? "hit " + std::to_string(h->plane) + " " + bits_of(h->t) : "miss";
}
inline std::string text_of(const TriangleIntersection& a) {
  // t's and the coordinates' bits only where the contract defines them (den ≠ 0) and they were asked for.
  std::string s = std::string(to_string(a.relation)) + " " + std::string(to_string(a.location)) +
                  (a.owned ? " owned" : " not-owned");
  if (a.location == TriangleLocation::none) return s;
  for (double x : {a.t, a.barycentric[0], a.barycentric[1], a.barycentric[2]}) s.append(" ").append(bits_of(x));
  return s;
}
inline std::string text_of(const TriangleClassification& c) {
  return std::string(to_string(c.relation)) + " " + std::string(to_string(c.location)) +
         (c.owned ? " owned" : " not-owned");
}
inline std::string text_of(const Vec3& v) { return bits_of(v.x) + "," + bits_of(v.y) + "," + bits_of(v.z); }
inline std::string text_of(const Ray& r) { return text_of(r.origin) + ";" + text_of(r.direction); }

// The part of environment_word() a call must leave as it found it: all of it, except inside a
// DefaultFpEnvironment scope, where the calls leave the flags they raise (the scope's end clears them)
// and the tests set this to the control bits.
inline std::uint64_t environment_compared = ~std::uint64_t{0};

// f()'s text, or "throws: what()"; with " (environment changed)" when the call did not leave the
// floating-point environment (the environment_compared part) exactly as it found it.
inline std::string guarded(const std::function<std::string()>& f) {
  const std::uint64_t before = environment_word() & environment_compared;
  std::string text;
  try {
    text = f();
  } catch (const std::exception& e) {
    text = std::string("throws: ") + e.what();
  }
  if ((environment_word() & environment_compared) != before) text += " (environment changed)";
  return text;
}

// The queries: every hard kind, subnormal-heavy (subnormal and t-underflow kinds three times as often),
// the two queries that broke under DAZ and FTZ before, and a few invalid ones.
inline std::vector<testkit::Query> environment_test_queries(std::size_t count, std::uint64_t seed) {
  std::vector<testkit::Query> q;
  q.push_back({{{0, 0, 0}, {1, 0, 0}}, {{5, 0, 0}, {0x1p-1070, 0, 0}}});  // hit 5; DAZ read the normal as zero
  q.push_back({{{0, 0, 0}, {1, 0, 0}}, {{0x1p-1070, 0, 0}, {1, 0, 0}}});  // hit 2^-1070; FTZ gave 0
  q.push_back({{{0, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {1, 0, 0}}});          // invalid: zero direction
  q.push_back({{{0, 0, 0}, {1, 0, 0}}, {{1, 0, 0}, {0, 0, 0}}});          // invalid: zero normal
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::QueryKind> kinds(testkit::all_query_kinds.begin(), testkit::all_query_kinds.end());
  for (int extra = 0; extra < 2; ++extra) {
    kinds.push_back(testkit::QueryKind::subnormal);
    kinds.push_back(testkit::QueryKind::t_underflow);
  }
  for (std::size_t i = 0; q.size() < count; ++i) q.push_back(testkit::make_query(kinds[i % kinds.size()], bits));
  return q;
}

// The ray–triangle queries: every hard kind, subnormal-heavy (the tiny kind, whose products all underflow,
// three times as often), a hand-derived subnormal triangle, and a few invalid queries.
inline std::vector<testkit::TriangleQuery> environment_test_triangle_queries(std::size_t count, std::uint64_t seed) {
  std::vector<testkit::TriangleQuery> q;
  // h = 2^-1070: a = 0, b = (h, 0, 0), c = (0, h, 0); the line x = y = h/4 crosses z = 0 at barycentric
  // coordinates (1 − 1/4 − 1/4, 1/4, 1/4) = (1/2, 1/4, 1/4), at t = 1 from z = −1. DAZ reads b and c as
  // zero, which makes the triangle degenerate; FTZ flushes every product.
  q.push_back({{{0x1p-1072, 0x1p-1072, -1}, {0, 0, 1}}, {{0, 0, 0}, {0x1p-1070, 0, 0}, {0, 0x1p-1070, 0}}});
  q.push_back({{{0, 0, 0}, {0, 0, 0}}, {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}});  // invalid: zero direction
  // invalid: a NaN vertex (from its bits: this file may be compiled with -ffast-math)
  q.push_back({{{0, 0, 0}, {1, 1, 1}}, {{1, 0, 0}, {0, std::bit_cast<double>(0x7ff8000000000000ULL), 0}, {0, 0, 1}}});
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::TriangleQueryKind> kinds(testkit::all_triangle_query_kinds.begin(),
                                                 testkit::all_triangle_query_kinds.end());
  kinds.push_back(testkit::TriangleQueryKind::tiny);
  kinds.push_back(testkit::TriangleQueryKind::tiny);
  for (std::size_t i = 0; q.size() < count; ++i) q.push_back(testkit::make_triangle_query(kinds[i % kinds.size()], bits));
  return q;
}

struct EntryPointAnswers {
  std::vector<std::string> names;                 // one per entry point
  std::vector<std::vector<std::string>> answers;  // answers[k][i]: entry point k, query i
  std::vector<bool> on_triangles;                 // entry point k answered the triangle queries
};

// Every public entry point on `queries` (the ray–plane ones) and `triangles` (the ray–triangle ones; the
// naive Möller–Trumbore runs in the caller's environment by design and is not among them). `exact_every`
// limits the slow exact ones (microseconds each) to every n-th query. Apart from the library's calls, the code
// does no floating-point arithmetic, so that it can run with traps enabled.
inline EntryPointAnswers answers_of_every_entry_point(const std::vector<testkit::Query>& queries,
                                                      const std::vector<testkit::TriangleQuery>& triangles,
                                                      std::size_t exact_every = 1) {
  EntryPointAnswers out;
  const std::size_t n = queries.size();
  auto add_over = [&](std::size_t count, bool on_triangles, const char* name,
                      const std::function<std::string(std::size_t)>& answer, std::size_t every) {
    out.names.emplace_back(name);
    out.on_triangles.push_back(on_triangles);
    std::vector<std::string>& a = out.answers.emplace_back();
    a.reserve(count);
    for (std::size_t i = 0; i < count; ++i) a.push_back(i % every == 0 ? guarded([&] { return answer(i); }) : "");
  };
  auto add = [&](const char* name, const std::function<std::string(std::size_t)>& answer, std::size_t every = 1) {
    add_over(n, false, name, answer, every);
  };
  auto ray = [&](std::size_t i) -> const Ray& { return queries[i].ray; };
  auto plane = [&](std::size_t i) -> const Plane& { return queries[i].plane; };
  // Three planes per ray for the nearest hit: the query's, the next query's, and the query's plane with
  // its point moved to the next query's origin (no arithmetic here: this code may run in a trapping mode).
  auto planes_of = [&](std::size_t i) {
    Plane moved = plane(i);
    moved.point = queries[(i + 1) % n].ray.origin;
    return std::vector<Plane>{plane(i), plane((i + 1) % n), moved};
  };

  add("intersect", [&](std::size_t i) { return text_of(intersect(ray(i), plane(i))); });
  add("relation", [&](std::size_t i) { return std::string(to_string(raykernel::relation(ray(i), plane(i)))); });
  add("intersect_traced", [&](std::size_t i) {
    const TracedIntersection t = intersect_traced(ray(i), plane(i));
    return text_of(t.intersection) + " " + std::string(to_string(t.relation_stage)) + " " +
           std::string(to_string(t.t_stage));
  });
  add("validate", [&](std::size_t i) {
    return validate(ray(i), plane(i)).value_or("") + "|" + validate(ray(i)).value_or("") + "|" +
           validate(plane(i)).value_or("");
  });
  add("nearest_hit", [&](std::size_t i) { return text_of(nearest_hit(ray(i), planes_of(i))); });
  add("nearest_hit(PlaneSet)", [&](std::size_t i) { return text_of(nearest_hit(ray(i), PlaneSet(planes_of(i)))); });
  add("nearest_hit_traced", [&](std::size_t i) {
    const TracedNearestHit t = nearest_hit_traced(ray(i), planes_of(i));
    return text_of(t.hit) + " " + std::string(to_string(t.relation_stage)) + " " +
           std::string(to_string(t.comparison_stage)) + " " + std::string(to_string(t.t_stage));
  });
  add("intersect_exact", [&](std::size_t i) { return text_of(intersect_exact(ray(i), plane(i))); }, exact_every);
  add("intersect_exact_rational", [&](std::size_t i) {
    const ExactIntersection e = intersect_exact_rational(ray(i), plane(i));
    return text_of(e.intersection) + " " + e.num.str() + " " + e.den.str() + " " + (e.t ? e.t->str() : "-");
  }, exact_every);
  add("round_rational_to_double", [&](std::size_t i) {
    // num/den of the query as exact integers: the rounding every exact t uses.
    const ExactIntersection e = intersect_exact_rational(ray(i), plane(i));
    return e.t ? bits_of(round_rational_to_double(e.t->numerator, e.t->denominator)) : std::string("-");
  }, exact_every);
  add("nearest_hit_exact", [&](std::size_t i) { return text_of(nearest_hit_exact(ray(i), planes_of(i))); }, exact_every);
  add("testkit::check_against_reference", [&](std::size_t i) {
    return testkit::check_against_reference(queries[i], intersect(ray(i), plane(i)), 0).report();
  }, exact_every);
  add("transforms", [&](std::size_t i) {
    // Exact cases: a translation of the origin by the plane's point when the sum is exact is checked by
    // transform_test; here the result only has to be the default environment's.
    const Transform t = Transform::translation(plane(i).point) * Transform::scaling({2, 0.5, 4});
    return text_of(transform_point(t, ray(i).origin)) + " " + text_of(transform_direction(t, ray(i).direction)) +
           " " + text_of(transform_ray(t, ray(i), Renormalize::yes));
  });
  add("cameras", [&](std::size_t i) {
    const ImageSize image{7, 5};
    const std::uint32_t px = static_cast<std::uint32_t>(i % 7), py = static_cast<std::uint32_t>(i / 7 % 5);
    const NearPlaneWindow window{-1.5, 1.25, -0.75, 1.0, 0x1p-3};
    const Camera camera = Camera::perspective(camera_to_world({0.25, 1.5, 6}, {0, 0.75, 0}, {0, 1, 0}), window, image);
    return text_of(ndc_ray(px, py, image)) + " " + text_of(perspective_ray(window, px, py, image)) + " " +
           text_of(orthographic_ray(window, px, py, image)) + " " + text_of(camera.ray(px, py, {0.3, 0.7}));
  });

  // Ray–triangle (raykernel/triangle.hpp).
  auto add_triangle = [&](const char* name, const std::function<std::string(std::size_t)>& answer,
                          std::size_t every = 1) { add_over(triangles.size(), true, name, answer, every); };
  auto tray = [&](std::size_t i) -> const Ray& { return triangles[i].ray; };
  auto tri = [&](std::size_t i) -> const Triangle& { return triangles[i].triangle; };
  const TriangleOptions closed_t_only{TriangleRule::closed, true, false};
  const TriangleOptions closed_coordinates_only{TriangleRule::closed, false, true};
  add_triangle("triangle intersect", [&](std::size_t i) { return text_of(intersect(tray(i), tri(i))); });
  add_triangle("triangle intersect (closed, t only)",
               [&](std::size_t i) { return text_of(intersect(tray(i), tri(i), closed_t_only)); });
  add_triangle("triangle intersect (closed, coordinates only)",
               [&](std::size_t i) { return text_of(intersect(tray(i), tri(i), closed_coordinates_only)); });
  add_triangle("triangle relation", [&](std::size_t i) {
    return text_of(raykernel::relation(tray(i), tri(i))) + " | " +
           text_of(raykernel::relation(tray(i), tri(i), TriangleRule::closed));
  });
  add_triangle("triangle intersect_traced", [&](std::size_t i) {
    const TracedTriangleIntersection t = intersect_traced(tray(i), tri(i));
    return text_of(t.intersection) + " " + std::string(to_string(t.relation_stage)) + " " +
           std::string(to_string(t.rounding_stage));
  });
  add_triangle("triangle validate", [&](std::size_t i) { return validate(tray(i), tri(i)).value_or("valid"); });
  add_triangle("triangle intersect_exact", [&](std::size_t i) { return text_of(intersect_exact(tray(i), tri(i))); },
               exact_every);
  add_triangle("triangle intersect_exact_rational", [&](std::size_t i) {
    const ExactTriangleIntersection e = intersect_exact_rational(tray(i), tri(i), TriangleRule::closed);
    std::string s = text_of(e.intersection) + " " + e.den.str() + " " + e.num.str() + " " + e.pi_a.str() + " " +
                    e.pi_b.str() + " " + e.pi_c.str();
    if (e.t) s.append(" ").append(e.t->str());
    return s;
  }, exact_every);
  add_triangle("triangle testkit::check_against_reference", [&](std::size_t i) {
    return testkit::check_against_reference(triangles[i], intersect(tray(i), tri(i)), TriangleRule::owned, 0).report();
  }, exact_every);

  // The batch forms, over all queries at once (two threads, so worker threads are covered too).
  std::vector<double> c[12];
  for (const testkit::Query& x : queries) {
    const double v[12] = {x.ray.origin.x, x.ray.origin.y, x.ray.origin.z, x.ray.direction.x, x.ray.direction.y,
                          x.ray.direction.z, x.plane.point.x, x.plane.point.y, x.plane.point.z, x.plane.normal.x,
                          x.plane.normal.y, x.plane.normal.z};
    for (int k = 0; k < 12; ++k) c[k].push_back(v[k]);
  }
  const RayBatch rays{c[0], c[1], c[2], c[3], c[4], c[5]};
  const PlaneBatch planes{c[6], c[7], c[8], c[9], c[10], c[11]};
  std::vector<Relation> relations(n);
  std::vector<double> t(n);
  std::unique_ptr<bool[]> valid(new bool[n]);
  const BatchOptions two_threads{.threads = 2};
  intersect_batch(rays, planes, {relations, t, {valid.get(), n}}, two_threads);
  add("intersect_batch", [&](std::size_t i) {
    return valid[i] ? text_of(Intersection{relations[i], t[i]}) : std::string("invalid");
  });
  std::vector<Relation> only(n);
  relation_batch(rays, planes, {only, {valid.get(), n}}, two_threads);
  add("relation_batch", [&](std::size_t i) { return valid[i] ? std::string(to_string(only[i])) : std::string("invalid"); });
  std::vector<Plane> valid_planes;
  for (const testkit::Query& x : queries)
    if (!validate(x.plane)) valid_planes.push_back(x.plane);
  valid_planes.resize(std::min<std::size_t>(valid_planes.size(), 16));
  std::vector<std::optional<NearestHit>> nearest(n);
  std::vector<double> vr[6];
  for (const testkit::Query& x : queries) {
    if (validate(x.ray)) continue;  // nearest_hit_batch throws for the first invalid ray
    const double v[6] = {x.ray.origin.x, x.ray.origin.y, x.ray.origin.z, x.ray.direction.x, x.ray.direction.y,
                         x.ray.direction.z};
    for (int k = 0; k < 6; ++k) vr[k].push_back(v[k]);
  }
  nearest.resize(vr[0].size());
  nearest_hit_batch({vr[0], vr[1], vr[2], vr[3], vr[4], vr[5]}, PlaneSet(valid_planes), nearest, two_threads);
  add("nearest_hit_batch", [&](std::size_t i) { return i < nearest.size() ? text_of(nearest[i]) : std::string(); });
  return out;
}

// Query i of entry point k, as text for a failure message.
inline std::string query_text(const EntryPointAnswers& a, std::size_t k, std::size_t i,
                              const std::vector<testkit::Query>& queries,
                              const std::vector<testkit::TriangleQuery>& triangles) {
  return a.on_triangles[k] ? testkit::to_string(triangles[i]) : testkit::to_string(queries[i]);
}

}  // namespace raykernel::test_support
