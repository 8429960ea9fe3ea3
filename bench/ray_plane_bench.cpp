// raykernel_bench: the cost of ray–plane queries on each path, measured in one run so that the ratios
// compare like with like (bench/README.md has the table, the machine and the command).
//
//   intersect/<path>/<workload>    naive, certified, batch_certified, exact, cgal_epeck (t from the point);
//                                  naive_soa on random_l2 (the naive formula over arrays, auto-vectorized)
//   relation/<path>/<workload>     certified (`relation`), batch_certified (`relation_batch`), cgal_epick
//                                  (CGAL's yes/no do_intersect)
//   {intersect,relation}/certified_scoped/<workload>
//                                  the certified calls inside one DefaultFpEnvironment scope (no per-call
//                                  read and restore of the floating-point environment)
//   memory/read/random             reading the random workload's arrays once: the floor for streaming
//   nearest/<path>/<set>           rays against a prepared plane set: naive, certified, exact;
//                                  demo4/demo64 (the demo camera's rays and planes), random4/random64
//   render/<path>/demo             the whole demo image, one sample per pixel: camera ray, nearest plane,
//                                  shading; naive or certified
//   render/<path>/octahedron       scenes/octahedron.json (a floor and a mesh), 400 × 400 × 4 rays: camera ray,
//                                  the nearest of the planes and triangles (one query, or the two naive loops),
//                                  shading
//   sweep/<path>/<k>               queries at angle 2^-k between ray and plane, k = 0, 4, ..., 100
//
// Workloads: random (2^20 queries, 96 MiB: streaming), random_l2 (2^12 queries: in L2), wide, degenerate,
// render. Items per second count queries (rays for nearest/ and render/). Every buffer is checked once
// (certified == exact) before anything is timed.
#include "cgal_baselines.hpp"
#include "workloads.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/camera.hpp>
#include <raykernel/fp_environment.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <benchmark/benchmark.h>

#include "rotate.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace raykernel::bench {
namespace {

// The fraction of the buffer's queries whose relation and whose t each stage of the cascade decided.
void add_stage_counters(benchmark::State& state, const std::vector<testkit::Query>& queries) {
  std::array<double, stage_count> relation{}, t{};
  double with_t = 0;
  for (const auto& q : queries) {
    const TracedIntersection r = intersect_traced(q.ray, q.plane);
    relation[static_cast<std::size_t>(r.relation_stage)] += 1;
    if (r.intersection.relation == Relation::hit || r.intersection.relation == Relation::behind) {
      t[static_cast<std::size_t>(r.t_stage)] += 1;
      with_t += 1;
    }
  }
  const double n = static_cast<double>(queries.size());
  for (std::size_t s = 0; s < stage_count; ++s) {
    const std::string name(to_string(static_cast<Stage>(s)));
    state.counters["rel_" + name] = relation[s] / n;
    if (s > 0) state.counters["t_" + name] = with_t > 0 ? t[s] / with_t : 0;
  }
}

unsigned all_threads() { return std::max(1u, std::thread::hardware_concurrency()); }

void register_workload(Workload w) {
  const std::string suffix = "/" + to_string(w);
  auto queries = [w] { return &workload(w); };
  benchmark::RegisterBenchmark(("intersect/naive" + suffix).c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), [](const testkit::Query& q) { return intersect_naive(q.ray, q.plane); });
  });
  benchmark::RegisterBenchmark(("intersect/certified" + suffix).c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), [](const testkit::Query& q) { return intersect(q.ray, q.plane); });
    add_stage_counters(s, *queries());
  });
  benchmark::RegisterBenchmark(("intersect/exact" + suffix).c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), [](const testkit::Query& q) { return intersect_exact(q.ray, q.plane); });
  });
  benchmark::RegisterBenchmark(("relation/certified" + suffix).c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), [](const testkit::Query& q) { return relation(q.ray, q.plane); });
  });
  // The same calls inside one DefaultFpEnvironment scope: the per-call environment check hoisted out.
  benchmark::RegisterBenchmark(("intersect/certified_scoped" + suffix).c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, *queries(), [](const testkit::Query& q) { return intersect(q.ray, q.plane); });
  });
  benchmark::RegisterBenchmark(("relation/certified_scoped" + suffix).c_str(), [queries](benchmark::State& s) {
    const DefaultFpEnvironment env;
    rotate_through(s, *queries(), [](const testkit::Query& q) { return relation(q.ray, q.plane); });
  });
  // The batch benchmarks run on all threads: they are timed by the wall clock (UseRealTime), not by the
  // calling thread's CPU time.
  benchmark::RegisterBenchmark(("intersect/batch_certified" + suffix).c_str(), [w, queries](benchmark::State& s) {
    // The batch API over the whole buffer per iteration, on all threads; checked once against intersect.
    const SoA& soa = workload_soa(w);
    const std::size_t n = soa.ox.size();
    std::vector<Relation> relation(n);
    std::vector<double> t(n);
    for (auto _ : s) {
      intersect_batch(soa.rays(), soa.planes(), {relation, t}, {.threads = all_threads()});
      benchmark::DoNotOptimize(t.data());
      benchmark::ClobberMemory();
    }
    s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(n));
    const std::vector<testkit::Query>& q = *queries();
    for (std::size_t i = 0; i < n; i += 97) {
      const Intersection a = intersect(q[i].ray, q[i].plane);
      if (a.relation != relation[i] || (a.relation <= Relation::behind && std::memcmp(&a.t, &t[i], sizeof a.t) != 0))
        return s.SkipWithError("batch != intersect");
    }
  })->UseRealTime();
  benchmark::RegisterBenchmark(("relation/batch_certified" + suffix).c_str(), [w, queries](benchmark::State& s) {
    const SoA& soa = workload_soa(w);
    const std::size_t n = soa.ox.size();
    std::vector<Relation> relation(n);
    for (auto _ : s) {
      relation_batch(soa.rays(), soa.planes(), {relation}, {.threads = all_threads()});
      benchmark::DoNotOptimize(relation.data());
      benchmark::ClobberMemory();
    }
    s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(n));
    const std::vector<testkit::Query>& q = *queries();
    for (std::size_t i = 0; i < n; i += 97)
      if (relation[i] != raykernel::relation(q[i].ray, q[i].plane)) return s.SkipWithError("batch != relation");
  })->UseRealTime();
  benchmark::RegisterBenchmark(("relation/cgal_epick" + suffix).c_str(), [queries](benchmark::State& s) {
    const EpickQueries cgal(*queries());
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [&cgal](std::size_t i) { return cgal.do_intersect(i); });
  });
  benchmark::RegisterBenchmark(("intersect/cgal_epeck" + suffix).c_str(), [queries](benchmark::State& s) {
    // Lazy exact objects are large: at most 2^16 queries of the workload (the cost is not memory-bound).
    const std::vector<testkit::Query>& q = *queries();
    const EpeckQueries cgal(std::vector<testkit::Query>(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(q.size(), 1 << 16))));
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [&cgal](std::size_t i) { return cgal.intersection_t(i); });
  });
}

void register_naive_soa_and_memory() {
  benchmark::RegisterBenchmark("intersect/naive_soa/random_l2", [](benchmark::State& s) {
    const SoA& soa = workload_soa(Workload::random_l2);
    const std::size_t n = soa.ox.size();
    std::vector<Relation> relation(n);
    std::vector<double> t(n);
    for (auto _ : s) {
      naive_soa(soa, relation.data(), t.data());
      benchmark::DoNotOptimize(t.data());
      benchmark::ClobberMemory();
    }
    s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(n));
  });
  benchmark::RegisterBenchmark("memory/read/random", [](benchmark::State& s) {
    const SoA& soa = workload_soa(Workload::random);
    for (auto _ : s) benchmark::DoNotOptimize(read_all(soa, all_threads()));
    s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(soa.ox.size()));
    s.counters["threads"] = all_threads();
  })->UseRealTime();
}

void register_nearest(const std::string& name) {
  auto run = [name](benchmark::State& s, auto nearest) {
    const NearestWorkload& w = nearest_workload(name);
    std::size_t i = 0;
    for (auto _ : s) {
      for (int k = 0; k < chunk; ++k) {
        auto r = nearest(w, w.rays[i]);
        benchmark::DoNotOptimize(r);
        if (++i == w.rays.size()) i = 0;
      }
    }
    s.SetItemsProcessed(s.iterations() * chunk);
  };
  benchmark::RegisterBenchmark(("nearest/naive/" + name).c_str(), [run](benchmark::State& s) {
    run(s, [](const NearestWorkload& w, const Ray& r) { return nearest_hit_naive(r, w.planes); });
  });
  benchmark::RegisterBenchmark(("nearest/certified/" + name).c_str(), [run](benchmark::State& s) {
    run(s, [](const NearestWorkload& w, const Ray& r) { return nearest_hit(r, w.prepared); });
  });
  benchmark::RegisterBenchmark(("nearest/exact/" + name).c_str(), [run](benchmark::State& s) {
    run(s, [](const NearestWorkload& w, const Ray& r) { return nearest_hit_exact(r, w.planes); });
  });
}

// sweep/<path>/<k>: queries at angle 2^-k between ray and plane (k = 0, 4, ..., 100), for the degeneracy
// plot (bench/plot-degeneracy.sh).
template <int K>
void register_sweep() {
  if constexpr (K <= 100) {
    const std::string suffix = "/" + std::to_string(K);
    benchmark::RegisterBenchmark(("sweep/naive" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, angle_sweep(K), [](const testkit::Query& q) { return intersect_naive(q.ray, q.plane); });
    });
    benchmark::RegisterBenchmark(("sweep/certified" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, angle_sweep(K), [](const testkit::Query& q) { return intersect(q.ray, q.plane); });
      add_stage_counters(s, angle_sweep(K));
    });
    benchmark::RegisterBenchmark(("sweep/exact" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, angle_sweep(K), [](const testkit::Query& q) { return intersect_exact(q.ray, q.plane); });
    });
    register_sweep<K + 4>();
  }
}

void register_render() {
  for (const bool certified : {false, true}) {
    benchmark::RegisterBenchmark(certified ? "render/certified/demo" : "render/naive/demo", [certified](benchmark::State& s) {
      const DemoRender& demo = demo_render();
      for (auto _ : s) benchmark::DoNotOptimize(demo.render_once(certified));
      s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(demo.pixels()));
    });
  }
  for (const bool certified : {false, true}) {
    benchmark::RegisterBenchmark(certified ? "render/certified/octahedron" : "render/naive/octahedron",
                                 [certified](benchmark::State& s) {
                                   const SceneRender& octahedron = octahedron_render();
                                   for (auto _ : s) benchmark::DoNotOptimize(octahedron.render_once(certified));
                                   s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) *
                                                       static_cast<std::int64_t>(octahedron.rays()));
                                 });
  }
}

}  // namespace
}  // namespace raykernel::bench

int main(int argc, char** argv) {
  using namespace raykernel::bench;
  for (Workload w : {Workload::random, Workload::random_l2, Workload::wide, Workload::degenerate, Workload::render})
    register_workload(w);
  register_naive_soa_and_memory();
  for (const char* set : {"demo4", "demo64", "random4", "random64"}) register_nearest(set);
  register_render();
  register_sweep<0>();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
