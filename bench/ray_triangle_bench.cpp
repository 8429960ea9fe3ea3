// The ray–triangle benchmarks (docs/contract.md §6), measured in the same run as the ray–plane ones:
//
//   triangle/<path>/<workload>
//     path:     naive       Möller–Trumbore in doubles (intersect_naive: t and the three coordinates)
//               certified   intersect: relation, location, owned flag, t and the three barycentric coordinates
//                           correctly rounded
//               relation    the relation-only form (relation, location, owned flag; nothing rounded)
//               certified_scoped, relation_scoped
//                           the same inside one DefaultFpEnvironment scope (no per-call environment check)
//               exact       intersect_exact (GMP rationals, MPFR)
//               cgal_epick  CGAL Epick do_intersect(Ray_3, Triangle_3): relation's like-for-like baseline
//               cgal_epeck  CGAL Epeck intersection(Ray_3, Triangle_3), t from the point
//     workload: random      4096 queries (every component uniform in [-1, 1]), 480 KiB: in L2
//               degenerate  4096 queries through vertices and edges exactly, an ulp beside them, slivers and
//                           needles (raykernel::testkit), in L2
//               through-vertex, through-edge, near-vertex, near-edge, sliver, needle
//                           4096 queries of that kind alone (naive, certified and relation only): the mix's time
//                           by kind
//
// Items per second count queries. The buffers are generated before timing and checked once (certified ==
// exact, both rules). The certified benchmarks report the fraction of the buffer each stage decided
// (rel_*: the relation; t_*: the roundings, queries with den ≠ 0), and exact_per_million.
// Registered at load time: main is ray_plane_bench.cpp's.
#include "cgal_triangle_baselines.hpp"

#include <raykernel/fp_environment.hpp>
#include <raykernel/testkit/triangle_queries.hpp>
#include <raykernel/triangle.hpp>

#include <benchmark/benchmark.h>

#include "rotate.hpp"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace raykernel::bench {
namespace {

using testkit::TriangleQuery;
using testkit::TriangleQueryKind;

constexpr std::size_t l2_size = 4096;

std::vector<TriangleQuery> generate(std::initializer_list<TriangleQueryKind> kinds, std::uint64_t seed) {
  return hard_query_buffer(kinds, seed, l2_size, testkit::make_triangle_query);
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b); }

void check(const std::vector<TriangleQuery>& queries, const char* name) {
  for (std::size_t i = 0; i < queries.size(); ++i)
    for (TriangleRule rule : {TriangleRule::owned, TriangleRule::closed}) {
      const TriangleIntersection a = intersect(queries[i].ray, queries[i].triangle, {rule, true, true});
      const TriangleIntersection b = intersect_exact(queries[i].ray, queries[i].triangle, {rule, true, true});
      bool ok = a.relation == b.relation && a.location == b.location && a.owned == b.owned && same(a.t, b.t);
      for (int k = 0; k < 3; ++k) ok = ok && same(a.barycentric[static_cast<std::size_t>(k)], b.barycentric[static_cast<std::size_t>(k)]);
      if (!ok) {
        std::fprintf(stderr, "raykernel_bench: certified != exact on triangle workload %s, query %zu\n", name, i);
        std::abort();
      }
    }
}

const std::vector<TriangleQuery>& random_workload() {
  static const std::vector<TriangleQuery> w = [] {
    auto q = generate({TriangleQueryKind::random}, 14);
    check(q, "random");
    return q;
  }();
  return w;
}

const std::vector<TriangleQuery>& degenerate_workload() {
  static const std::vector<TriangleQuery> w = [] {
    auto q = generate({TriangleQueryKind::through_vertex, TriangleQueryKind::through_edge, TriangleQueryKind::near_vertex,
                       TriangleQueryKind::near_edge, TriangleQueryKind::sliver, TriangleQueryKind::needle},
                      15);
    check(q, "degenerate");
    return q;
  }();
  return w;
}

void add_stage_counters(benchmark::State& state, const std::vector<TriangleQuery>& queries) {
  std::array<double, 4> relation{}, rounding{};
  double crossing = 0;
  for (const TriangleQuery& q : queries) {
    const TracedTriangleIntersection r = intersect_traced(q.ray, q.triangle);
    relation[static_cast<std::size_t>(r.relation_stage)] += 1;
    if (r.intersection.location != TriangleLocation::none) {
      rounding[static_cast<std::size_t>(r.rounding_stage)] += 1;
      crossing += 1;
    }
  }
  const double n = static_cast<double>(queries.size());
  const char* names[4] = {"filter", "compensated", "expansion", "exact"};
  for (std::size_t s = 0; s < 4; ++s) {
    state.counters[std::string("rel_") + names[s]] = relation[s] / n;
    if (s > 0) state.counters[std::string("t_") + names[s]] = crossing > 0 ? rounding[s] / crossing : 0;
  }
  state.counters["exact_per_million"] = 1e6 * (relation[3] + rounding[3]) / n;
}

using Workload = const std::vector<TriangleQuery>& (*)();

// The naive, certified and relation rows of a workload.
void register_main_paths(const std::string& workload, Workload queries) {
  auto name = [&workload](const char* path) { return std::string("triangle/") + path + "/" + workload; };
  benchmark::RegisterBenchmark(name("naive").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const TriangleQuery& q) { return intersect_naive(q.ray, q.triangle); });
  });
  benchmark::RegisterBenchmark(name("certified").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const TriangleQuery& q) { return intersect(q.ray, q.triangle); });
    add_stage_counters(s, queries());
  });
  benchmark::RegisterBenchmark(name("relation").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const TriangleQuery& q) { return relation(q.ray, q.triangle); });
  });
}

void register_workload(const char* workload, Workload queries) {
  auto name = [workload](const char* path) { return std::string("triangle/") + path + "/" + workload; };
  register_main_paths(workload, queries);
  // The same calls inside one DefaultFpEnvironment scope: the per-call environment check hoisted out.
  benchmark::RegisterBenchmark(name("certified_scoped").c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, queries(), [](const TriangleQuery& q) { return intersect(q.ray, q.triangle); });
  });
  benchmark::RegisterBenchmark(name("relation_scoped").c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, queries(), [](const TriangleQuery& q) { return relation(q.ray, q.triangle); });
  });
  benchmark::RegisterBenchmark(name("exact").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, queries(), [](const TriangleQuery& q) { return intersect_exact(q.ray, q.triangle); });
  });
  benchmark::RegisterBenchmark(name("cgal_epick").c_str(), [queries](benchmark::State& s) {
    // CGAL's precondition excludes degenerate triangles: they are skipped in the rotation.
    static std::vector<std::size_t> index;
    static const EpickTriangles* cgal = nullptr;
    if (cgal == nullptr) {
      std::vector<TriangleQuery> kept;
      for (const TriangleQuery& q : queries())
        if (intersect_exact(q.ray, q.triangle).relation != TriangleRelation::degenerate) kept.push_back(q);
      cgal = new EpickTriangles(kept);
      for (std::size_t i = 0; i < kept.size(); ++i) index.push_back(i);
    }
    std::size_t i = 0;
    for (auto _ : s) {
      for (int k = 0; k < chunk; ++k) {
        benchmark::DoNotOptimize(cgal->do_intersect(index[i]));
        if (++i == index.size()) i = 0;
      }
    }
    s.SetItemsProcessed(s.iterations() * chunk);
  });
  benchmark::RegisterBenchmark(name("cgal_epeck").c_str(), [queries](benchmark::State& s) {
    static std::vector<std::size_t> index;
    static const EpeckTriangles* cgal = nullptr;
    if (cgal == nullptr) {
      std::vector<TriangleQuery> kept;
      for (const TriangleQuery& q : queries())
        if (intersect_exact(q.ray, q.triangle).relation != TriangleRelation::degenerate) kept.push_back(q);
      cgal = new EpeckTriangles(kept);
      for (std::size_t i = 0; i < kept.size(); ++i) index.push_back(i);
    }
    std::size_t i = 0;
    for (auto _ : s) {
      for (int k = 0; k < chunk; ++k) {
        benchmark::DoNotOptimize(cgal->intersection_t(index[i]));
        if (++i == index.size()) i = 0;
      }
    }
    s.SetItemsProcessed(s.iterations() * chunk);
  });
}

// One kind of the degenerate mix alone (4096 queries, checked like the others): which kinds the mix's time goes
// to. Rows triangle/{naive,certified,relation}/<kind>, e.g. triangle/relation/through-vertex.
template <TriangleQueryKind Kind>
const std::vector<TriangleQuery>& kind_workload() {
  static const std::vector<TriangleQuery> w = [] {
    auto q = generate({Kind}, 16);
    check(q, std::string(testkit::to_string(Kind)).c_str());
    return q;
  }();
  return w;
}

template <TriangleQueryKind... Kinds>
void register_kinds() {
  (register_main_paths(std::string(testkit::to_string(Kinds)), &kind_workload<Kinds>), ...);
}

const bool registered = [] {
  register_workload("random", &random_workload);
  register_workload("degenerate", &degenerate_workload);
  register_kinds<TriangleQueryKind::through_vertex, TriangleQueryKind::through_edge, TriangleQueryKind::near_vertex,
                 TriangleQueryKind::near_edge, TriangleQueryKind::sliver, TriangleQueryKind::needle>();
  return true;
}();

}  // namespace
}  // namespace raykernel::bench
