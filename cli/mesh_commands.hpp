// The mesh commands of the raykernel CLI (docs/contract.md §7): `raykernel inside --mesh FILE [POINTS|-]`,
// `raykernel nearest --mesh FILE [--rule=owned|closed] [RAYS|-]` and `raykernel watertight FILE`, runnable on
// streams so that tests and the CLI fuzzers drive the same code as the binary.
#pragma once

#include "commands.hpp"

#include <raykernel/mesh_queries.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::cli {

// The mesh prepared for queries (its BVH built), with "not enough memory" naming it (failure.hpp).
[[nodiscard]] PreparedMesh prepare_mesh(Mesh&& mesh, const std::string& path);

// The mesh in a file, or nothing after printing "raykernel: FILE:LINE: REASON" (or "FILE: byte N: REASON",
// "FILE: REASON") on `err` (docs/contract.md §7: an unreadable mesh is exit status 2, nothing on stdout).
[[nodiscard]] std::optional<Mesh> read_mesh_file(const std::string& path, std::ostream& err);

struct InsideCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t by_location[3] = {};  // by raykernel::PointLocation
};

// Answers every point line of `in` (`x y z`) with `inside`, `outside` or `on-surface`; invalid lines as §3.
// Returns exit_ok or exit_invalid_line.
int inside_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                  InsideCounts& counts);

struct MeshNearestOptions {
  Method method = Method::certified;  // exact: every triangle in rationals (nearest_hit_exact); naive:
                                      // Möller–Trumbore via the BVH (nearest_hit_naive)
  TriangleRule rule = TriangleRule::owned;
  bool exact_t = false;  // append the winner's exact t as P/Q
  bool hex = false;
  bool stats = false;
};

struct MeshNearestCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t hits = 0;
  std::uint64_t misses = 0;
  // The certified path's work, summed over the rays (nearest_hit_traced): candidate triangles, the stage that
  // decided each relation (and those repeating the previous candidate), ties of the rounded t settled from the
  // vertices, and the stage of the other ties' comparisons.
  std::uint64_t candidates = 0, repeats = 0, ties = 0, ties_without_arithmetic = 0;
  std::uint64_t relation_stage[stage_count] = {};
  std::uint64_t comparison_stage[stage_count] = {};
};

// Answers every ray line of `rays` (`ox oy oz dx dy dz`) with `hit K T` (K the triangle index) or `miss`, as
// nearest_stream does for planes (docs/contract.md §4, §7). Returns exit_ok or exit_invalid_line.
int mesh_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                        const MeshNearestOptions& options, MeshNearestCounts& counts);

// `raykernel inside --mesh FILE [POINTS|-]` and `raykernel watertight FILE [options]` (argv without the program
// and subcommand names). `raykernel nearest` calls run_mesh_nearest when given --mesh.
int run_inside(const std::vector<std::string>& args);
int run_mesh_nearest(const std::string& mesh_path, const std::string& rays_path, const MeshNearestOptions& options);
int run_watertight(const std::vector<std::string>& args);

}  // namespace raykernel::cli
