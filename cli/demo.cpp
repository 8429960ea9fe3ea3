// raykernel demo: a built-in batch of hard classify queries, answered by the certified, exact and naive
// paths, with a per-kind summary of relations, deciding stages and naive mistakes.
#include "commands.hpp"

#include <raykernel/testkit/hard_queries.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* demo_help = R"(usage: raykernel demo [--per-kind N] [--seed S]

Generates N queries (default 20000) of each kind of hard ray-plane query (near-parallel rays,
origins a few ulps from the plane, exact degeneracies, rounding ties, extreme exponents, ...),
answers each with the certified, exact and naive paths, and prints per kind the relations found,
which certified stage decided them, and how often the naive formula in doubles was wrong.
Exit status 0 when certified == exact on every query, 3 otherwise (a bug: please report it).
)";

bool same_answer(const Intersection& a, const Intersection& b) {
  if (a.relation != b.relation) return false;
  if (a.relation == Relation::parallel || a.relation == Relation::in_plane) return true;
  return std::memcmp(&a.t, &b.t, sizeof(double)) == 0;  // bit-identical t, signed zeros included
}

struct KindTally {
  std::uint64_t queries = 0, relation[4] = {}, relation_stage[4] = {}, t_stage[4] = {};
  std::uint64_t naive_wrong_relation = 0, naive_wrong_t = 0, mismatches = 0;
};

}  // namespace

int run_demo(const std::vector<std::string>& args) {
  long per_kind = 20000;
  std::uint64_t seed = 1;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a == "--help" || a == "-h") {
      std::cout << demo_help;
      return exit_ok;
    }
    if ((a == "--per-kind" || a == "--seed") && i + 1 < args.size()) {
      char* end = nullptr;
      const unsigned long long v = std::strtoull(args[i + 1].c_str(), &end, 10);
      if (*end != '\0' || args[i + 1].empty() || (a == "--per-kind" && (v == 0 || v > 100000000))) {
        std::cerr << "raykernel demo: bad value for " << a << ": '" << args[i + 1] << "'\n";
        return exit_usage;
      }
      if (a == "--seed") seed = v;
      else per_kind = static_cast<long>(v);
      ++i;
    } else {
      std::cerr << "raykernel demo: unknown argument '" << a << "' (see raykernel demo --help)\n";
      return exit_usage;
    }
  }

  using testkit::QueryKind;
  std::printf("raykernel %s demo: %ld queries of each of %d kinds (seed %llu)\n\n", std::string(version()).c_str(),
              per_kind, testkit::query_kind_count, static_cast<unsigned long long>(seed));
  std::printf("%-16s %7s %7s %8s %8s | %-31s | %s\n", "", "hit", "behind", "parallel", "in-plane",
              "relation decided by stage", "naive formula wrong");
  std::printf("%-16s %7s %7s %8s %8s | %7s %7s %7s %7s | %9s %9s\n", "kind", "", "", "", "", "filter", "compens",
              "expans", "exact", "relation", "t bits");

  KindTally total;
  double seconds[3] = {0, 0, 0};  // certified, exact, naive
  testkit::SplitMix64 rng(seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::Query> batch(static_cast<std::size_t>(per_kind));
  std::vector<Intersection> certified(batch.size()), exact(batch.size()), naive(batch.size());
  std::vector<TracedIntersection> traced(batch.size());
  for (QueryKind kind : testkit::all_query_kinds) {
    for (auto& q : batch) q = testkit::make_query(kind, bits);
    using clock = std::chrono::steady_clock;
    auto t0 = clock::now();
    for (std::size_t i = 0; i < batch.size(); ++i) traced[i] = intersect_traced(batch[i].ray, batch[i].plane);
    auto t1 = clock::now();
    for (std::size_t i = 0; i < batch.size(); ++i) exact[i] = intersect_exact(batch[i].ray, batch[i].plane);
    auto t2 = clock::now();
    for (std::size_t i = 0; i < batch.size(); ++i) naive[i] = intersect_naive(batch[i].ray, batch[i].plane);
    auto t3 = clock::now();
    seconds[0] += std::chrono::duration<double>(t1 - t0).count();
    seconds[1] += std::chrono::duration<double>(t2 - t1).count();
    seconds[2] += std::chrono::duration<double>(t3 - t2).count();

    KindTally k;
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const Intersection& c = traced[i].intersection;
      ++k.queries;
      ++k.relation[static_cast<int>(exact[i].relation)];
      ++k.relation_stage[static_cast<int>(traced[i].relation_stage)];
      if (!same_answer(c, exact[i])) ++k.mismatches;
      if (naive[i].relation != exact[i].relation) ++k.naive_wrong_relation;
      else if (!same_answer(naive[i], exact[i])) ++k.naive_wrong_t;
    }
    auto pct = [&](std::uint64_t n) { return 100.0 * static_cast<double>(n) / static_cast<double>(k.queries); };
    std::printf("%-16s %7llu %7llu %8llu %8llu | %6.1f%% %6.1f%% %6.1f%% %6.1f%% | %8.1f%% %8.1f%%\n",
                std::string(to_string(kind)).c_str(), static_cast<unsigned long long>(k.relation[0]),
                static_cast<unsigned long long>(k.relation[1]), static_cast<unsigned long long>(k.relation[2]),
                static_cast<unsigned long long>(k.relation[3]), pct(k.relation_stage[0]), pct(k.relation_stage[1]),
                pct(k.relation_stage[2]), pct(k.relation_stage[3]), pct(k.naive_wrong_relation),
                pct(k.naive_wrong_t));
    total.queries += k.queries;
    total.mismatches += k.mismatches;
    total.naive_wrong_relation += k.naive_wrong_relation;
    total.naive_wrong_t += k.naive_wrong_t;
    for (int s = 0; s < 4; ++s) {
      total.relation[s] += k.relation[s];
      total.relation_stage[s] += k.relation_stage[s];
    }
  }

  const double n = static_cast<double>(total.queries);
  std::printf("\n%llu queries: %llu hit, %llu behind, %llu parallel, %llu in-plane\n",
              static_cast<unsigned long long>(total.queries), static_cast<unsigned long long>(total.relation[0]),
              static_cast<unsigned long long>(total.relation[1]), static_cast<unsigned long long>(total.relation[2]),
              static_cast<unsigned long long>(total.relation[3]));
  std::printf("relation decided by the filter %.1f%%, compensated %.1f%%, expansion %.1f%%, exact %.1f%%\n",
              100 * static_cast<double>(total.relation_stage[0]) / n,
              100 * static_cast<double>(total.relation_stage[1]) / n,
              100 * static_cast<double>(total.relation_stage[2]) / n,
              100 * static_cast<double>(total.relation_stage[3]) / n);
  std::printf("naive formula in doubles: wrong relation on %.1f%%, wrong t (same relation) on %.1f%%\n",
              100 * static_cast<double>(total.naive_wrong_relation) / n,
              100 * static_cast<double>(total.naive_wrong_t) / n);
  std::printf("mean time per query: certified %.0f ns, exact %.0f ns, naive %.1f ns (informal; see bench/)\n",
              1e9 * seconds[0] / n, 1e9 * seconds[1] / n, 1e9 * seconds[2] / n);
  if (total.mismatches != 0) {
    std::printf("BUG: certified and exact disagree on %llu queries\n",
                static_cast<unsigned long long>(total.mismatches));
    return 3;
  }
  std::printf("certified == exact on all %llu queries (relation and the bits of t)\n",
              static_cast<unsigned long long>(total.queries));
  return exit_ok;
}

}  // namespace raykernel::cli
