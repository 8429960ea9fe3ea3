// raykernel sphere (docs/contract.md §10): one ray–sphere query per line, runnable on streams so that tests and
// the CLI fuzzer drive the same code as the binary.
#pragma once

#include "common/stream_command.hpp"

#include <raykernel/sphere.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace raykernel::cli {

struct SphereCommandOptions {
  Method method = Method::certified;  // --path
  bool exact = false;                 // --exact: append U V as P/Q (the roots are U ∓ √V)
  bool hex = false;                   // print the roots as hexadecimal floats
  bool stats = false;                 // print per-relation and per-stage counts to stderr
};

struct SphereCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t origin[3] = {};          // by raykernel::SphereOrigin
  std::uint64_t relation[3] = {};        // by raykernel::SphereRelation
  std::uint64_t relation_stage[4] = {};  // by raykernel::Stage (certified path)
  std::uint64_t rounding_stage[4] = {};  // by raykernel::Stage, for lines with roots (certified path)
};

// Answers every query line of `in` (10 numbers: ox oy oz dx dy dz cx cy cz r) on `out`: `ORIGIN miss`,
// `ORIGIN tangent T0` or `ORIGIN cross T1 T2` (with --exact, then `U V`); invalid lines as §3 says. Returns
// exit_ok or exit_invalid_line.
int sphere_stream(std::istream& in, std::ostream& out, std::ostream& err, const SphereCommandOptions& options,
                  SphereCounts& counts);

// What --stats prints.
std::string describe(const SphereCounts& counts, Method method);

}  // namespace raykernel::cli
