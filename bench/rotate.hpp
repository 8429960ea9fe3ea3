// What every per-query benchmark shares: the timed loop, `chunk` queries per iteration, rotating through a buffer
// generated before timing (so the loop measures the calls, not the generation), items counted as queries; and the
// generation of such a buffer from the testkit's hard queries.
#pragma once

#include <raykernel/testkit/plane_queries.hpp>

#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
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

// `count` hard queries, the kinds taken in turn, drawn from SplitMix64(seed) by `make(kind, bits)` (a testkit
// constructor): a benchmark's buffer, generated before timing.
template <class Kind, class Make>
auto hard_query_buffer(std::initializer_list<Kind> kinds, std::uint64_t seed, std::size_t count, Make make) {
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  const std::vector<Kind> k(kinds);
  std::vector<decltype(make(k[0], bits))> out(count);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = make(k[i % k.size()], bits);
  return out;
}

}  // namespace raykernel::bench
