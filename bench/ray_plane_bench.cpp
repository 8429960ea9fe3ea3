// raykernel_bench: the cost of one ray–plane query on each path, measured in one run so that the ratios
// compare like with like.
//
//   intersect/<path>/<workload>   path: naive, certified, exact, cgal_epick, cgal_epeck
//                                 workload: random, wide, degenerate
//   sweep/<path>/<k>              queries at angle 2^-k between ray and plane (k = 0, 4, ..., 100)
//
// Items per second count ray–plane queries. Each benchmark rotates through a pre-generated buffer (96 MiB
// for the workloads, beyond the last-level cache) that was checked once (certified == exact). The certified
// benchmarks report, as counters, the fraction of the buffer's queries whose relation (rel_*) and whose t
// (t_*) each stage decided.
#include "cgal_baselines.hpp"
#include "workloads.hpp"

#include <raykernel/raykernel.hpp>

#include <benchmark/benchmark.h>

#include <array>
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

void add_stage_counters(benchmark::State& state, const std::vector<testing::Query>& queries) {
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

auto naive = [](const testing::Query& q) { return intersect_naive(q.ray, q.plane); };
auto certified = [](const testing::Query& q) { return intersect(q.ray, q.plane); };
auto exact = [](const testing::Query& q) { return intersect_exact(q.ray, q.plane); };

void register_path_benchmarks(const std::string& workload_name, const std::vector<testing::Query>* (*queries)(),
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
  if (!with_cgal) return;
  benchmark::RegisterBenchmark(name("cgal_epick").c_str(), [queries](benchmark::State& s) {
    static const EpickQueries cgal(*queries());
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [](std::size_t i) { return cgal.do_intersect(i); });
  });
  benchmark::RegisterBenchmark(name("cgal_epeck").c_str(), [queries](benchmark::State& s) {
    // Lazy exact objects are large: 2^16 queries of the workload (the cost is not memory-bound anyway).
    static const EpeckQueries cgal(std::vector<testing::Query>(queries()->begin(), queries()->begin() + (1 << 16)));
    std::vector<std::size_t> index(cgal.size());
    for (std::size_t i = 0; i < index.size(); ++i) index[i] = i;
    rotate_through(s, index, [](std::size_t i) { return cgal.intersection_t(i); });
  });
}

template <Workload W>
const std::vector<testing::Query>* workload_queries() {
  return &workload(W);
}
template <int K>
const std::vector<testing::Query>* sweep_queries() {
  return &angle_sweep(K);
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
  register_sweep<0>();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
