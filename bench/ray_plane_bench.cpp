// raykernel_bench: the cost of one ray–plane query on each path, measured in one run so that the ratios
// compare like with like.
//
//   intersect/<path>/<workload>   path: naive, certified, exact, cgal_epick, cgal_epeck, batch_certified
//                                 workload: random, wide, degenerate, render
//   nearest/<path>/<planes>       the demo camera's rays against 4 or 64 planes: naive, certified, exact
//                                 (items: rays; one nearest hit each)
//   sweep/<path>/<k>              queries at angle 2^-k between ray and plane (k = 0, 4, ..., 100)
//
// Items per second count ray–plane queries. Each benchmark rotates through a pre-generated buffer (96 MiB
// for the workloads, beyond the last-level cache) that was checked once (certified == exact). The certified
// benchmarks report, as counters, the fraction of the buffer's queries whose relation (rel_*) and whose t
// (t_*) each stage decided.
#include "cgal_baselines.hpp"
#include "workloads.hpp"

#include <raykernel/batch.hpp>
#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <benchmark/benchmark.h>

#include <array>
#include <cstring>
#include <span>
#include <string>

namespace raykernel::bench {
namespace {

constexpr int chunk = 256;  // queries per benchmark iteration

template <class Query, class F>
void rotate_through(benchmark::State& state, const std::vector<Query>& queries, F&& f) {
  std::size_t i = 0;
  const std::size_t n = queries.size();
  for (auto _ : state) {
    for (int k = 0; k < chunk; ++k) {
      auto r = f(queries[i]);
      benchmark::DoNotOptimize(r);
      if (++i == n) i = 0;
    }
  }
  state.SetItemsProcessed(state.iterations() * chunk);
}

void add_stage_counters(benchmark::State& state, const std::vector<testkit::Query>& queries) {
  std::array<double, 4> relation{}, t{};
  double with_t = 0;
  for (const auto& q : queries) {
    const TracedIntersection r = intersect_traced(q.ray, q.plane);
    relation[static_cast<int>(r.relation_stage)] += 1;
    if (r.intersection.relation == Relation::hit || r.intersection.relation == Relation::behind) {
      t[static_cast<int>(r.t_stage)] += 1;
      with_t += 1;
    }
  }
  const double n = static_cast<double>(queries.size());
  const char* names[4] = {"filter", "compensated", "expansion", "exact"};
  for (int s = 0; s < 4; ++s) {
    state.counters[std::string("rel_") + names[s]] = relation[static_cast<std::size_t>(s)] / n;
    if (s > 0) state.counters[std::string("t_") + names[s]] = with_t > 0 ? t[static_cast<std::size_t>(s)] / with_t : 0;
  }
}

auto naive = [](const testkit::Query& q) { return intersect_naive(q.ray, q.plane); };
auto certified = [](const testkit::Query& q) { return intersect(q.ray, q.plane); };
auto exact = [](const testkit::Query& q) { return intersect_exact(q.ray, q.plane); };

void register_path_benchmarks(const std::string& workload_name, const std::vector<testkit::Query>* (*queries)(),
                              bool with_cgal) {
  auto name = [&](const char* path) { return "intersect/" + std::string(path) + "/" + workload_name; };
  benchmark::RegisterBenchmark(name("naive").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), naive);
  });
  benchmark::RegisterBenchmark(name("certified").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), certified);
    add_stage_counters(s, *queries());
  });
  benchmark::RegisterBenchmark(name("exact").c_str(), [queries](benchmark::State& s) {
    rotate_through(s, *queries(), exact);
  });
  benchmark::RegisterBenchmark(name("batch_certified").c_str(), [queries, workload_name](benchmark::State& s) {
    // The batch API over the whole buffer per iteration (threads: all cores), counted per query.
    const Workload w = workload_name == "random" ? Workload::random
                       : workload_name == "wide" ? Workload::wide
                       : workload_name == "degenerate" ? Workload::degenerate
                                                       : Workload::render;
    const SoA& soa = workload_soa(w);
    const std::size_t n = soa.ox.size();
    std::vector<Relation> relation(n);
    std::vector<double> t(n);
    BatchStats stats;
    for (auto _ : s) {
      intersect_batch({soa.ox, soa.oy, soa.oz, soa.dx, soa.dy, soa.dz}, {soa.px, soa.py, soa.pz, soa.nx, soa.ny, soa.nz},
                      {relation, t}, {.stats = &stats});
      benchmark::DoNotOptimize(t.data());
      benchmark::ClobberMemory();
    }
    s.SetItemsProcessed(static_cast<std::int64_t>(s.iterations()) * static_cast<std::int64_t>(n));
    // Checked once: the batch answers are intersect's.
    const std::vector<testkit::Query>& q = *queries();
    for (std::size_t i = 0; i < n; i += 97) {
      const Intersection a = intersect(q[i].ray, q[i].plane);
      if (a.relation != relation[i] || (a.relation <= Relation::behind && std::memcmp(&a.t, &t[i], sizeof a.t) != 0)) {
        s.SkipWithError("batch != intersect");
        return;
      }
    }
    const double total = static_cast<double>(s.iterations()) * static_cast<double>(n);
    s.counters["rel_filter"] = static_cast<double>(stats.relation_stage[0]) / total;
    s.counters["rel_compensated"] = static_cast<double>(stats.relation_stage[1]) / total;
    s.counters["rel_expansion"] = static_cast<double>(stats.relation_stage[2]) / total;
    s.counters["rel_exact"] = static_cast<double>(stats.relation_stage[3]) / total;
  });
  if (!with_cgal) return;
  benchmark::RegisterBenchmark(name("cgal_epick").c_str(), [queries](benchmark::State& s) {
    static const EpickQueries cgal(*queries());
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [](std::size_t i) { return cgal.do_intersect(i); });
  });
  benchmark::RegisterBenchmark(name("cgal_epeck").c_str(), [queries](benchmark::State& s) {
    // Lazy exact objects are large: 2^16 queries of the workload (the cost is not memory-bound anyway).
    static const EpeckQueries cgal(std::vector<testkit::Query>(queries()->begin(), queries()->begin() + (1 << 16)));
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [](std::size_t i) { return cgal.intersection_t(i); });
  });
}

template <Workload W>
const std::vector<testkit::Query>* workload_queries() {
  return &workload(W);
}
template <int K>
const std::vector<testkit::Query>* sweep_queries() {
  return &angle_sweep(K);
}

void register_nearest(std::size_t planes) {
  const std::string suffix = "/" + std::to_string(planes);
  auto run = [planes](benchmark::State& s, auto nearest) {
    const NearestWorkload& w = nearest_workload(planes);
    std::size_t i = 0;
    for (auto _ : s) {
      for (int k = 0; k < chunk; ++k) {
        auto r = nearest(w.rays[i], std::span<const Plane>(w.planes));
        benchmark::DoNotOptimize(r);
        if (++i == w.rays.size()) i = 0;
      }
    }
    s.SetItemsProcessed(s.iterations() * chunk);
  };
  benchmark::RegisterBenchmark(("nearest/naive" + suffix).c_str(), [run](benchmark::State& s) {
    run(s, [](const Ray& r, std::span<const Plane> p) { return nearest_hit_naive(r, p); });
  });
  benchmark::RegisterBenchmark(("nearest/certified" + suffix).c_str(), [run, planes](benchmark::State& s) {
    run(s, [](const Ray& r, std::span<const Plane> p) { return nearest_hit(r, p); });
    // Counters: the slowest stage each ray needed, over the whole image.
    const NearestWorkload& w = nearest_workload(planes);
    std::array<double, 4> slowest{};
    for (const Ray& r : w.rays) slowest[static_cast<std::size_t>(std::max(nearest_hit_traced(r, w.planes).relation_stage, nearest_hit_traced(r, w.planes).comparison_stage))] += 1;
    const char* names[4] = {"filter", "compensated", "expansion", "exact"};
    for (int k = 0; k < 4; ++k)
      s.counters[std::string("ray_") + names[k]] = slowest[static_cast<std::size_t>(k)] / static_cast<double>(w.rays.size());
  });
  benchmark::RegisterBenchmark(("nearest/exact" + suffix).c_str(), [run](benchmark::State& s) {
    run(s, [](const Ray& r, std::span<const Plane> p) { return nearest_hit_exact(r, p); });
  });
}

template <int K>
void register_sweep() {
  if constexpr (K <= 100) {
    const std::string prefix = "sweep/";
    const std::string suffix = "/" + std::to_string(K);
    benchmark::RegisterBenchmark((prefix + "naive" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, *sweep_queries<K>(), naive);
    });
    benchmark::RegisterBenchmark((prefix + "certified" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, *sweep_queries<K>(), certified);
      add_stage_counters(s, *sweep_queries<K>());
    });
    benchmark::RegisterBenchmark((prefix + "exact" + suffix).c_str(), [](benchmark::State& s) {
      rotate_through(s, *sweep_queries<K>(), exact);
    });
    register_sweep<K + 4>();
  }
}

}  // namespace
}  // namespace raykernel::bench

int main(int argc, char** argv) {
  using namespace raykernel::bench;
  register_path_benchmarks("random", &workload_queries<Workload::random>, true);
  register_path_benchmarks("wide", &workload_queries<Workload::wide>, true);
  register_path_benchmarks("degenerate", &workload_queries<Workload::degenerate>, true);
  register_path_benchmarks("render", &workload_queries<Workload::render>, true);
  register_nearest(4);
  register_nearest(64);
  register_sweep<0>();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
