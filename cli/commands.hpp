// The subcommands of the raykernel CLI, runnable on streams so that tests and the CLI fuzzer drive the same
// code as the binary.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include <raykernel/raykernel.hpp>

namespace raykernel::cli {

// Exit statuses (CONTRACT §3).
inline constexpr int exit_ok = 0;
inline constexpr int exit_invalid_line = 1;
inline constexpr int exit_usage = 2;

enum class Path { certified, exact, naive };

struct ClassifyOptions {
  Path path = Path::certified;
  bool exact_t = false;  // append the exact t as P/Q
  bool hex = false;      // print T as a hexadecimal float
  bool stats = false;    // print per-relation and per-stage counts to stderr
};

// Counts of one classify run.
struct ClassifyCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t relation[4] = {};        // by raykernel::Relation
  std::uint64_t relation_stage[4] = {};  // by raykernel::Stage (certified path)
  std::uint64_t t_stage[4] = {};         // by raykernel::Stage, for hit and behind (certified path)
};

// Answers every query line of `in` on `out` (CONTRACT §3); invalid lines are also reported on `err` as
// "raykernel: line N: REASON". Returns exit_ok or exit_invalid_line.
int classify_stream(std::istream& in, std::ostream& out, std::ostream& err, const ClassifyOptions& options,
                    ClassifyCounts& counts);

// Human-readable summary of counts (what --stats prints).
std::string describe(const ClassifyCounts& counts, Path path);

// `raykernel classify [options] [FILE|-]`, `raykernel demo [options]`: argv excludes the program and
// subcommand names.
int run_classify(const std::vector<std::string>& args);
int run_demo(const std::vector<std::string>& args);

}  // namespace raykernel::cli
