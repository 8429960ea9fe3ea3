// raykernel nearest --planes (docs/contract.md §4): the first plane each ray hits, runnable on streams so that
// tests and the CLI fuzzers drive the same code as the binary. (nearest --mesh: mesh_nearest.hpp.)
#pragma once

#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <raykernel/raykernel.hpp>

#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

namespace raykernel::cli {

struct NearestOptions {
  Method method = Method::certified;
  bool exact_t = false;  // append the winner's exact t as P/Q
  bool hex = false;      // print T as a hexadecimal float
  bool stats = false;    // print per-stage counts to stderr
};

// Counts of one nearest run. Per ray: the slowest stage any plane's relation needed, and the stage that
// rounded the winner's t; comparisons of two t values are counted one by one (certified path only).
struct NearestCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t hits = 0;
  std::uint64_t misses = 0;
  std::uint64_t relation_stage[4] = {};    // by raykernel::Stage
  std::uint64_t comparison_stage[4] = {};  // by raykernel::Stage
  std::uint64_t t_stage[4] = {};           // by raykernel::Stage, for hits
};

// The planes of a planes file (`px py pz nx ny nz` per line; blank and # lines skipped; a byte-order mark at
// the start skipped; plane K is the K-th plane line from 0), or the first invalid line: its number (counting
// every line from 1) and the reason.
using PlanesFile = PrimitiveFile<Plane>;
[[nodiscard]] PlanesFile read_planes(std::istream& in);

// Answers every ray line of `rays` (`ox oy oz dx dy dz`) on `out` with `hit K T` or `miss` (docs/contract.md §4);
// invalid lines get `invalid REASON` on `out` and "raykernel: line N: REASON" on `err`. Like classify_stream,
// skips a byte-order mark and stops reading as soon as `out` fails. Returns exit_ok or exit_invalid_line.
// `planes` must be valid (read_planes checks them).
int nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, std::span<const Plane> planes,
                   const NearestOptions& options, NearestCounts& counts);

// Human-readable summary of counts (what nearest --stats prints).
std::string describe(const NearestCounts& counts, Method method);

}  // namespace raykernel::cli
