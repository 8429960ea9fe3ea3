// raykernel nearest --mesh FILE [--rule=owned|closed] [RAYS|-] (docs/contract.md §4, §7): the first triangle of
// a mesh each ray hits, runnable on streams so that tests drive the same code as the binary.
#pragma once

#include "common/stream_command.hpp"

#include <raykernel/mesh_queries.hpp>

#include <cstdint>
#include <iosfwd>
#include <string>

namespace raykernel::cli {

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
  // decided each relation (and those repeating the previous candidate), near ties (hits the filter could not
  // order against the best so far) settled from the vertices, and the stage of the other near ties' comparisons.
  std::uint64_t candidates = 0, repeats = 0, ties = 0, ties_without_arithmetic = 0;
  std::uint64_t relation_stage[stage_count] = {};
  std::uint64_t comparison_stage[stage_count] = {};
};

// Answers every ray line of `rays` (`ox oy oz dx dy dz`) with `hit K T` (K the triangle index) or `miss`, as
// nearest_stream does for planes (docs/contract.md §4, §7). Returns exit_ok or exit_invalid_line.
int mesh_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                        const MeshNearestOptions& options, MeshNearestCounts& counts);

// What `raykernel nearest` runs when given --mesh: the mesh file, the rays file ("-": standard input).
int run_mesh_nearest(const std::string& mesh_path, const std::string& rays_path, const MeshNearestOptions& options);

}  // namespace raykernel::cli
