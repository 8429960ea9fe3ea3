// raykernel classify (docs/contract.md §3): one ray–plane query per line, runnable on streams so that tests
// and the CLI fuzzer drive the same code as the binary.
#pragma once

#include "common/stream_command.hpp"

#include <raykernel/raykernel.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace raykernel::cli {

struct ClassifyOptions {
  Method method = Method::certified;
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

// Answers every query line of `in` on `out` (docs/contract.md §3); invalid lines are also reported on `err` as
// "raykernel: line N: REASON". A UTF-8 byte-order mark at the start of `in` is skipped. Stops reading as soon
// as `out` fails (a closed pipe, a full disk): the caller reports that. Returns exit_ok or exit_invalid_line.
int classify_stream(std::istream& in, std::ostream& out, std::ostream& err, const ClassifyOptions& options,
                    ClassifyCounts& counts);

// Human-readable summary of counts (what --stats prints).
std::string describe(const ClassifyCounts& counts, Method method);

}  // namespace raykernel::cli
