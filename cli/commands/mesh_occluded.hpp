// raykernel occluded --mesh FILE [--segment] [--rule=owned|closed] [RAYS|-] (docs/contract.md §8): whether
// anything blocks each ray in its interval, or each open segment, runnable on streams so that tests drive the same
// code as the binary.
#pragma once

#include "common/stream_command.hpp"

#include <raykernel/occlusion.hpp>

#include <cstdint>
#include <iosfwd>

namespace raykernel::cli {

struct MeshOccludedOptions {
  Method method = Method::certified;  // exact: every triangle in rationals (occluded_exact)
  TriangleRule rule = TriangleRule::owned;
  bool segment = false;  // lines of two points p q (the open segment between them), not rays
};

struct MeshOccludedCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t occluded = 0;
  std::uint64_t clear = 0;
};

// Answers every line of `in` with `occluded` or `clear`: ray lines `ox oy oz dx dy dz [t_min t_max]` (t_max may be
// inf), or with options.segment, segment lines `px py pz qx qy qz`; invalid lines as §3 (a bad interval or p = q
// named). Returns exit_ok or exit_invalid_line.
int mesh_occluded_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                         const MeshOccludedOptions& options, MeshOccludedCounts& counts);

}  // namespace raykernel::cli
