#include "workloads.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>

namespace raykernel::bench {
namespace {

using testing::QueryKind;
using testing::SplitMix64;

std::vector<Query> generate(QueryKind kind, std::uint64_t seed, std::size_t count) {
  SplitMix64 rng(seed);
  const testing::BitSource bits = [&rng] { return rng(); };
  std::vector<Query> out(count);
  for (auto& q : out) q = testing::make_query(kind, bits);
  return out;
}

std::vector<Query> degenerate_mix(std::size_t count) {
  SplitMix64 rng(3);
  const testing::BitSource bits = [&rng] { return rng(); };
  std::vector<Query> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = testing::make_query(i % 2 == 0 ? QueryKind::near_parallel : QueryKind::near_coplanar, bits);
  return out;
}

// d = (n2·s, −n1·s, 2^-k·c) against n = (n1, n2, n3): the first two terms of d·n cancel exactly (20-bit
// integers: every product is exact), so d·n = 2^-k·c·n3 exactly and the angle between ray and plane is
// about 2^-k. Axes are then shuffled so that the tiny component is not always z.
std::vector<Query> sweep(int k, std::size_t count) {
  SplitMix64 rng(1000 + static_cast<std::uint64_t>(k));
  auto integer = [&rng] { return static_cast<double>(static_cast<std::int64_t>(rng() % (1u << 20)) - (1 << 19)) + 0.5; };
  auto unit = [&rng] { return static_cast<double>(static_cast<std::int64_t>(rng() >> 11) - (std::int64_t{1} << 52)) * 0x1p-52; };
  std::vector<Query> out(count);
  for (auto& q : out) {
    const double n1 = integer(), n2 = integer(), n3 = integer(), s = integer();
    const double d[3] = {n2 * s, -n1 * s, std::ldexp(integer(), -k) * std::ldexp(1.0, 19)};
    const double n[3] = {n1, n2, n3};
    const double o[3] = {unit(), unit(), unit()};
    const double p[3] = {unit(), unit(), unit()};
    const int r = static_cast<int>(rng() % 3);  // rotate axes
    auto at = [r](const double* v, int i) { return v[(i + r) % 3]; };
    q = {{{at(o, 0), at(o, 1), at(o, 2)}, {at(d, 0), at(d, 1), at(d, 2)}},
         {{at(p, 0), at(p, 1), at(p, 2)}, {at(n, 0), at(n, 1), at(n, 2)}}};
  }
  return out;
}

// Certified == exact on every query of the buffer (on the first 2^16 for the exact path's sake: it takes
// microseconds per query). A mismatch is a bug: abort before anything is timed.
void check(const std::vector<Query>& queries, const std::string& name) {
  const std::size_t n = queries.size() < (std::size_t{1} << 16) ? queries.size() : (std::size_t{1} << 16);
  for (std::size_t i = 0; i < n; ++i) {
    const Intersection a = intersect(queries[i].ray, queries[i].plane);
    const Intersection b = intersect_exact(queries[i].ray, queries[i].plane);
    const bool t_matters = a.relation == Relation::hit || a.relation == Relation::behind;
    if (a.relation != b.relation || (t_matters && std::memcmp(&a.t, &b.t, sizeof a.t) != 0)) {
      std::fprintf(stderr, "raykernel_bench: certified != exact on %s query %zu\n", name.c_str(), i);
      std::abort();
    }
  }
}

}  // namespace

std::string to_string(Workload w) {
  switch (w) {
    case Workload::random: return "random";
    case Workload::wide: return "wide";
    case Workload::degenerate: return "degenerate";
  }
  return "?";
}

const std::vector<Query>& workload(Workload w) {
  static std::mutex mutex;
  static std::map<Workload, std::vector<Query>> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find(w);
  if (it == cache.end()) {
    std::vector<Query> q;
    switch (w) {
      case Workload::random: q = generate(QueryKind::random, 1, workload_size); break;
      case Workload::wide: q = generate(QueryKind::wide_exponents, 2, workload_size); break;
      case Workload::degenerate: q = degenerate_mix(workload_size); break;
    }
    check(q, to_string(w));
    it = cache.emplace(w, std::move(q)).first;
  }
  return it->second;
}

const std::vector<Query>& angle_sweep(int k) {
  static std::mutex mutex;
  static std::map<int, std::vector<Query>> cache;
  const std::lock_guard lock(mutex);
  auto it = cache.find(k);
  if (it == cache.end()) {
    std::vector<Query> q = sweep(k, std::size_t{1} << 16);
    check(q, "angle 2^-" + std::to_string(k));
    it = cache.emplace(k, std::move(q)).first;
  }
  return it->second;
}

}  // namespace raykernel::bench
