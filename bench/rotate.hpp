// The timed loop every per-query benchmark shares: `chunk` queries per iteration, rotating through a buffer
// generated before timing (so the loop measures the calls, not the generation), items counted as queries.
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace raykernel::bench {

inline constexpr int chunk = 256;  // queries per benchmark iteration

template <class Item, class F>
void rotate_through(benchmark::State& state, const std::vector<Item>& items, F&& f) {
  std::size_t i = 0;
  const std::size_t n = items.size();
  for (auto _ : state) {
    for (int k = 0; k < chunk; ++k) {
      auto r = f(items[i]);
      benchmark::DoNotOptimize(r);
      if (++i == n) i = 0;
    }
  }
  state.SetItemsProcessed(state.iterations() * chunk);
}

}  // namespace raykernel::bench
