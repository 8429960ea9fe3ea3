// The subcommands of the raykernel CLI, runnable on streams so that tests and the CLI fuzzer drive the same
// code as the binary.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include <raykernel/raykernel.hpp>

namespace raykernel::cli {

// Exit statuses (docs/contract.md §3).
inline constexpr int exit_ok = 0;
inline constexpr int exit_invalid_line = 1;
inline constexpr int exit_usage = 2;

// The computation that answers (the --path option): the certified cascade, exact rationals alone, or the
// textbook formula in plain doubles (no guarantee).
enum class Method { certified, exact, naive };

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

// ---- nearest (docs/contract.md §4) ------------------------------------------------------------------------------

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
struct PlanesFile {
  std::vector<Plane> planes;
  std::uint64_t error_line = 0;  // 0 when every line was valid
  std::string error;
  [[nodiscard]] bool ok() const noexcept { return error_line == 0; }
};
[[nodiscard]] PlanesFile read_planes(std::istream& in);

// Answers every ray line of `rays` (`ox oy oz dx dy dz`) on `out` with `hit K T` or `miss` (docs/contract.md §4);
// invalid lines get `invalid REASON` on `out` and "raykernel: line N: REASON" on `err`. Like classify_stream,
// skips a byte-order mark and stops reading as soon as `out` fails. Returns exit_ok or exit_invalid_line.
// `planes` must be valid (read_planes checks them).
int nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, std::span<const Plane> planes,
                   const NearestOptions& options, NearestCounts& counts);

// Human-readable summary of counts (what nearest --stats prints).
std::string describe(const NearestCounts& counts, Method method);

// `raykernel classify [options] [FILE|-]`, `raykernel demo [options]`, `raykernel nearest --planes FILE
// [options] [RAYS|-]`, `raykernel render [SCENE.json] [options]`: argv excludes the program and subcommand
// names; "--" ends the options. Each writes through std::cout and returns exit_usage (2) after "raykernel:
// I/O error writing standard output: REASON" when its output could not be written (io.hpp).
int run_classify(const std::vector<std::string>& args);
int run_demo(const std::vector<std::string>& args);
int run_nearest(const std::vector<std::string>& args);
int run_render(const std::vector<std::string>& args);

}  // namespace raykernel::cli
