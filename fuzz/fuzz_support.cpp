#include "fuzz_support.hpp"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace raykernel::fuzz {
namespace {

struct Context {
  std::string harness = "?";
  std::function<std::string()> describe;
  std::string input_file;
};
Context& context() {
  static Context c;
  return c;
}

std::function<void()>& exit_printer() {
  static std::function<void()> print;
  return print;
}

}  // namespace

void set_harness_name(std::string_view name) { context().harness = name; }
void set_input_describer(std::function<std::string()> describe) { context().describe = std::move(describe); }
void set_current_input_file(std::string path) { context().input_file = std::move(path); }

void fail(std::string_view what) {
  const Context& c = context();
  std::fprintf(stderr, "\n==== raykernel fuzz_%s: CHECK FAILED: %.*s\n", c.harness.c_str(),
               static_cast<int>(what.size()), what.data());
  if (c.describe) std::fprintf(stderr, "%s\n", c.describe().c_str());
  if (!c.input_file.empty()) {
    std::fprintf(stderr, "input file: %s\nreproduce: fuzz_%s_replay %s\n", c.input_file.c_str(), c.harness.c_str(),
                 c.input_file.c_str());
  } else {
    std::fprintf(stderr, "libFuzzer saves this input (crash-<sha1>); reproduce: build-fuzz/fuzz/fuzz_%s <file>\n",
                 c.harness.c_str());
  }
  std::fflush(stderr);
  std::abort();
}

std::string hex(double x) {
  if (std::isnan(x)) return std::signbit(x) ? "-nan" : "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}

std::string bits_of(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(std::bit_cast<std::uint64_t>(x)));
  return buf;
}

bool stats_requested() {
  const char* v = std::getenv("RAYKERNEL_FUZZ_STATS");
  return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

void StageCounts::add(const TracedIntersection& traced) {
  ++executions;
  const auto relation_index = static_cast<std::size_t>(traced.intersection.relation);
  const auto relation_stage_index = static_cast<std::size_t>(traced.relation_stage);
  const auto t_stage_index = static_cast<std::size_t>(traced.t_stage);
  ++relation[relation_index];
  ++relation_stage[relation_stage_index];
  if (traced.intersection.relation == Relation::hit || traced.intersection.relation == Relation::behind)
    ++t_stage[t_stage_index];
  ++deepest[relation_stage_index > t_stage_index ? relation_stage_index : t_stage_index];
}

StageCounts& StageCounts::operator+=(const StageCounts& o) {
  executions += o.executions;
  invalid += o.invalid;
  for (std::size_t k = 0; k < 4; ++k) {
    relation[k] += o.relation[k];
    relation_stage[k] += o.relation_stage[k];
    t_stage[k] += o.t_stage[k];
    deepest[k] += o.deepest[k];
  }
  return *this;
}

std::string percent_text(std::uint64_t part, std::uint64_t whole) {
  if (whole == 0) return "     -";
  char buf[16];
  std::snprintf(buf, sizeof buf, "%6.2f", 100.0 * static_cast<double>(part) / static_cast<double>(whole));
  return buf;
}

std::string shares_text(const std::array<std::uint64_t, 4>& counts) {
  std::uint64_t whole = 0;
  for (std::uint64_t x : counts) whole += x;
  std::string s;
  for (std::uint64_t x : counts) {
    s += ' ';
    s += percent_text(x, whole);
  }
  return s;
}

std::string format_stage_table(std::string_view title, const std::vector<std::pair<std::string, StageCounts>>& rows) {
  std::string out = "==== raykernel fuzz stats: " + std::string(title) + " (percentages)\n";
  out +=
      "  relation: the answers of valid executions (hit, behind, parallel, in-plane)\n"
      "  relation stage: the stage that decided the relation (filter, compensated, expansion, exact), valid "
      "executions\n"
      "  t stage: the stage that decided t, hit and behind only\n"
      "  deepest: the slowest stage a valid execution needed\n";
  // Each group is four columns " %6s" wide (28 characters) followed by " |".
  auto group = [](const char* a, const char* b, const char* c, const char* d) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " %6s %6s %6s %6s |", a, b, c, d);
    return std::string(buf);
  };
  char head[256];
  std::snprintf(head, sizeof head, "%-16s %10s %7s |%-28s |%-28s |%-28s |%-28s |\n", "", "", "", " relation",
                " relation stage", " t stage", " deepest stage");
  out += head;
  std::snprintf(head, sizeof head, "%-16s %10s %7s |", "mode", "execs", "invalid");
  out += head;
  out += group("hit", "behind", "para", "inpl") + group("filt", "comp", "expa", "exact") +
         group("filt", "comp", "expa", "exact") + group("filt", "comp", "expa", "exact") + "\n";
  StageCounts total;
  auto row = [&](const std::string& name, const StageCounts& c) {
    char line[512];
    std::snprintf(line, sizeof line, "%-16s %10llu %7s |%s |%s |%s |%s |\n", name.c_str(),
                  static_cast<unsigned long long>(c.executions), percent_text(c.invalid, c.executions).c_str(),
                  shares_text(c.relation).c_str(), shares_text(c.relation_stage).c_str(), shares_text(c.t_stage).c_str(),
                  shares_text(c.deepest).c_str());
    out += line;
  };
  for (const auto& [name, counts] : rows) {
    if (counts.executions == 0) continue;
    row(name, counts);
    total += counts;
  }
  if (rows.size() > 1) row("all", total);
  return out;
}

void print_at_exit(std::function<void()> print) {
  if (!stats_requested()) return;
  static std::once_flag once;
  std::call_once(once, [&] {
    exit_printer() = std::move(print);
    std::atexit([] { exit_printer()(); });
  });
}

}  // namespace raykernel::fuzz
