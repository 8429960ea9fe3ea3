// raykernel closest --mesh FILE [POINTS|-] (docs/contract.md §11): the exact closest point of a mesh to each
// point, runnable on streams so that tests drive the same code as the binary.
#pragma once

#include <raykernel/closest_point.hpp>

#include <cstdint>
#include <iosfwd>

namespace raykernel::cli {

struct ClosestCounts {
  std::uint64_t lines_answered = 0;
  std::uint64_t invalid = 0;
  std::uint64_t by_feature[3] = {};  // by raykernel::ClosestFeature
};

// Answers every point line of `in` (`x y z`) with `TRIANGLE FEATURE CORNER X Y Z D2 DISTANCE SIGNED D2_EXACT`
// (`signed` adds the signed distance); invalid lines as §3. Returns exit_ok or exit_invalid_line.
int closest_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh, bool with_sign,
                   ClosestCounts& counts);

}  // namespace raykernel::cli
