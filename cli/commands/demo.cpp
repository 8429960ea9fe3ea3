// raykernel demo: a built-in batch of hard classify queries, answered by the certified, exact and naive
// paths, with a per-kind summary of relations, deciding stages and naive mistakes.
#include "commands/commands.hpp"
#include "common/exit_status.hpp"
#include "common/io.hpp"
#include "common/limits.hpp"
#include "common/options.hpp"
#include "common/text_format.hpp"

#include <raykernel/testkit/plane_queries.hpp>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel demo [--per-kind N] [--seed S]

Generates N queries of each kind of hard ray-plane query (near-parallel rays, origins a few ulps
from the plane, exact degeneracies, rounding ties, extreme exponents, ...), answers each with the
certified, exact and naive paths, and prints per kind the relations found, which certified stage
decided them, and how often the naive formula in doubles was wrong.
)";

constexpr const char* help_after = R"(exit status: 0 when certified == exact on every query, 2 for a usage error or when standard
output cannot be written, 3 when certified != exact somewhere (a bug: please report it).
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

// What the command line says.
struct Arguments {
  std::uint64_t per_kind = 20000;
  std::uint64_t seed = 1;
};

CommandLine command_line(Arguments& a) {
  return {.command = "demo",
          .options = {{"--per-kind", integer(a.per_kind, 1, limits::max_demo_queries_per_kind),
                       "queries of each kind (default 20000)"},
                      {"--seed", integer(a.seed, 0, UINT64_MAX, "S"), "the seed of the queries (default 1)"}},
          .operand = std::nullopt,
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

OwnedCommandLine demo_command_line() { return owned_command_line(command_line); }

int run_demo(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;

  using testkit::QueryKind;
  std::cout << formatted("raykernel %s demo: %llu queries of each of %d kinds (seed %llu)\n\n",
                         std::string(version()).c_str(), static_cast<unsigned long long>(arguments.per_kind),
                         testkit::query_kind_count, static_cast<unsigned long long>(arguments.seed));
  // The stage columns are as wide as the longest stage name.
  std::cout << formatted("%-16s %7s %7s %8s %8s | %-47s | %s\n", "", "hit", "behind", "parallel", "in-plane",
                         "relation decided by stage", "naive formula wrong");
  std::cout << formatted("%-16s %7s %7s %8s %8s |", "kind", "", "", "", "");
  for (int s = 0; s < stage_count; ++s) std::cout << formatted(" %11s", std::string(to_string(static_cast<Stage>(s))).c_str());
  std::cout << formatted(" | %9s %9s\n", "relation", "t bits");
  if (!flush_standard_output()) return exit_usage;

  KindTally total;
  double seconds[3] = {0, 0, 0};  // certified, exact, naive
  testkit::SplitMix64 rng(arguments.seed);
  const testkit::BitSource bits = [&rng] { return rng(); };
  std::vector<testkit::Query> batch(static_cast<std::size_t>(arguments.per_kind));
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
    auto pct = [&](std::uint64_t n) { return percent(n, k.queries, 1); };
    std::cout << formatted("%-16s %7llu %7llu %8llu %8llu | %11s %11s %11s %11s | %9s %9s\n",
                           std::string(to_string(kind)).c_str(), static_cast<unsigned long long>(k.relation[0]),
                           static_cast<unsigned long long>(k.relation[1]), static_cast<unsigned long long>(k.relation[2]),
                           static_cast<unsigned long long>(k.relation[3]), pct(k.relation_stage[0]).c_str(),
                           pct(k.relation_stage[1]).c_str(), pct(k.relation_stage[2]).c_str(),
                           pct(k.relation_stage[3]).c_str(), pct(k.naive_wrong_relation).c_str(),
                           pct(k.naive_wrong_t).c_str());
    if (!flush_standard_output()) return exit_usage;  // nobody reads the rest: stop
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
  const std::uint64_t all = total.queries;
  std::cout << '\n' << count_of(all, "query", "queries") << ": " << with_thousands(total.relation[0]) << " hit, "
            << with_thousands(total.relation[1]) << " behind, " << with_thousands(total.relation[2]) << " parallel, "
            << with_thousands(total.relation[3]) << " in-plane\n";
  std::cout << "relation decided by the " << to_string(Stage::filter) << " " << percent(total.relation_stage[0], all, 1);
  for (int s = 1; s < stage_count; ++s)
    std::cout << ", " << to_string(static_cast<Stage>(s)) << " " << percent(total.relation_stage[s], all, 1);
  std::cout << "\nnaive formula in doubles: wrong relation on " << percent(total.naive_wrong_relation, all, 1)
            << ", wrong t (same relation) on " << percent(total.naive_wrong_t, all, 1) << "\n";
  std::cout << formatted("mean time per query: certified %.0f ns, exact %.0f ns, naive %.1f ns (informal; see bench/)\n",
                         1e9 * seconds[0] / n, 1e9 * seconds[1] / n, 1e9 * seconds[2] / n);
  if (total.mismatches != 0) {
    std::cout << "BUG: certified and exact disagree on " << count_of(total.mismatches, "query", "queries") << "\n";
    return finish_standard_output(3);
  }
  std::cout << "certified == exact on all " << count_of(all, "query", "queries") << " (relation and the bits of t)\n";
  return finish_standard_output(exit_ok);
}

}  // namespace raykernel::cli
