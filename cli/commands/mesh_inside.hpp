// raykernel inside --mesh FILE [POINTS|-] (docs/contract.md §7): whether each point is inside a closed mesh,
// runnable on streams so that tests drive the same code as the binary.
#pragma once

#include <raykernel/mesh_queries.hpp>

#include <cstdint>
#include <iosfwd>

namespace raykernel::cli {

struct InsideCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t by_location[3] = {};  // by raykernel::PointLocation
};

// Answers every point line of `in` (`x y z`) with `inside`, `outside` or `on-surface`; invalid lines as §3.
// Returns exit_ok or exit_invalid_line.
int inside_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                  InsideCounts& counts);

}  // namespace raykernel::cli
