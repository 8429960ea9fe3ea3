// raykernel spawn (docs/contract.md §9): the origin of a secondary ray that never re-hits the triangle it
// leaves, one query per line, runnable on streams so that tests drive the same code as the binary.
#pragma once

#include <raykernel/spawn.hpp>

#include <cstdint>
#include <iosfwd>

namespace raykernel::cli {

struct SpawnCommandOptions {
  OriginFormat format = OriginFormat::binary64;  // --float: binary32
  bool point = false;                            // --point: the hit point given as p (15 numbers)
  bool to = false;                               // --to: a target point q in place of the direction w
  bool sphere = false;                           // --sphere: leaving a sphere (10 numbers px py pz cx cy cz r wx wy wz)
};

struct SpawnCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t moved = 0;  // answers with k ≥ 1: the rounded hit point was not strictly on the side
};

// Answers every line of `in` (18 numbers `ox oy oz dx dy dz ax ay az bx by bz cx cy cz wx wy wz`, or with
// `point` 15: `px py pz ax ... cz wx wy wz`; with `to`, `qx qy qz` in place of w; with `sphere` 10: `px py pz cx cy
// cz r wx wy wz`, the sphere's rule of raykernel/spawn.hpp) with `X Y Z K` (each
// coordinate printed so that it reads back exactly in the origin's format); invalid lines as §3 says. Returns
// exit_ok or exit_invalid_line.
int spawn_stream(std::istream& in, std::ostream& out, std::ostream& err, const SpawnCommandOptions& options,
                 SpawnCounts& counts);

}  // namespace raykernel::cli
