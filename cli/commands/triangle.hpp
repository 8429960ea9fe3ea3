// raykernel triangle (docs/contract.md §6): one ray–triangle query per line, runnable on streams so that tests
// and the CLI fuzzer drive the same code as the binary.
#pragma once

#include "common/stream_command.hpp"

#include <raykernel/triangle.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace raykernel::cli {

struct TriangleCommandOptions {
  Method method = Method::certified;  // --path
  TriangleRule rule = TriangleRule::owned;
  bool exact_t = false;  // --exact: append the exact t, UA, UB, UC as P/Q
  bool hex = false;      // print T, UA, UB, UC as hexadecimal floats
  bool stats = false;    // print per-relation and per-stage counts to stderr
};

struct TriangleCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t relation[6] = {};        // by raykernel::TriangleRelation
  std::uint64_t location[9] = {};        // by raykernel::TriangleLocation
  std::uint64_t relation_stage[4] = {};  // by raykernel::Stage (certified path)
  std::uint64_t rounding_stage[4] = {};  // by raykernel::Stage, for lines with t (certified path)
};

// Answers every query line of `in` (15 numbers: ox oy oz dx dy dz ax ay az bx by bz cx cy cz) on `out`:
// `degenerate`, `parallel`, `coplanar`, or `REL LOC T UA UB UC` (docs/contract.md §6); invalid lines as §3 says
// (`invalid REASON` on `out`, "raykernel: line N: REASON" on `err`). As classify_stream: a UTF-8 byte-order mark
// at the start is skipped, and reading stops as soon as `out` fails. Returns exit_ok or exit_invalid_line.
int triangle_stream(std::istream& in, std::ostream& out, std::ostream& err, const TriangleCommandOptions& options,
                    TriangleCounts& counts);

// What --stats prints.
std::string describe(const TriangleCounts& counts, Method method);

}  // namespace raykernel::cli
