// raykernel nearest --spheres FILE and raykernel occluded --spheres FILE [--segment] (docs/contract.md §8, §10;
// the CLI is decided in docs/contract.md): the first sphere each ray hits in its interval, and whether any sphere
// blocks a ray or an open segment, runnable on streams so that tests drive the same code as the binary.
#pragma once

#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <raykernel/sphere.hpp>

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>

namespace raykernel::cli {

// A spheres file: one sphere per line, `cx cy cz r` (§3's numbers; blank and # lines skipped). The first invalid
// line stops the reading (error_line, error name it; no spheres then).
using SpheresFile = PrimitiveFile<Sphere>;
[[nodiscard]] SpheresFile read_spheres(std::istream& in);

struct SphereSetOptions {
  Method method = Method::certified;  // exact: every root and bound in rationals
  bool segment = false;               // occluded: lines of two points p q, not rays
  bool hex = false;                   // nearest: T as a hexadecimal float
};

struct SphereSetCounts {
  std::uint64_t lines_answered = 0, invalid = 0, hits = 0, misses = 0;
};

// nearest: `hit K T` (K the sphere's index, T = RN of its smallest root in the ray's interval) or `miss` per ray
// line (`ox oy oz dx dy dz [t_min t_max]`); occluded: `occluded` or `clear` per ray or segment line. Invalid lines
// as §3. Return exit_ok or exit_invalid_line.
int sphere_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const SphereSet& spheres,
                          const SphereSetOptions& options, SphereSetCounts& counts);
int sphere_occluded_stream(std::istream& lines, std::ostream& out, std::ostream& err, const SphereSet& spheres,
                           const SphereSetOptions& options, SphereSetCounts& counts);

// What the commands run when given --spheres: the spheres file, then the input ("-": standard input).
int run_sphere_nearest(const std::string& spheres_path, const std::string& rays_path, const SphereSetOptions& options,
                       bool stats);
int run_sphere_occluded(const std::string& spheres_path, const std::string& input_path,
                        const SphereSetOptions& options, bool stats);

}  // namespace raykernel::cli
