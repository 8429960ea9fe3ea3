// raykernel inside: whether each point is inside a closed mesh (docs/contract.md §7).
#include "commands/mesh_inside.hpp"

#include "commands/commands.hpp"
#include "commands/mesh_file.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <iostream>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel inside --mesh FILE [options] [--] [POINTS|-]

For each point, whether it is inside the closed triangle mesh in FILE (OBJ, PLY, STL, OFF or glTF):
  on-surface   the point lies on some triangle (its plane, inside or on its boundary), exactly
  inside       else, the winding number is not 0
  outside      else
The winding number is the signed count of the owned crossings (raykernel triangle --help) of a
ray from the point (along an axis, towards the nearest face of the mesh's bounding box); for a
closed, consistently oriented mesh it is the same for every ray. Everything is decided exactly.

  POINTS  one point per line: x y z (standard input when POINTS is - or absent)

Numbers, blank and # lines, invalid lines and the byte-order mark as for classify; each point
line gives one output line: inside | outside | on-surface | invalid REASON.
)";

constexpr const char* help_after = R"(exit status: 0 every point valid, 1 some point line invalid, 2 usage or I/O error or a file
that is not a mesh (reported as raykernel: FILE:LINE: REASON, nothing on standard output)
)";

// What the command line says.
struct Arguments {
  std::optional<std::string> mesh_path, points_path;
  bool stats = false;
};

CommandLine command_line(Arguments& a) {
  return {.command = "inside",
          .options = {{"--mesh", file(a.mesh_path),
                       "the mesh (required; the format from the extension, else from the content)"},
                      {"--stats", flag(a.stats),
                       "print to stderr how many points were inside, outside and on the surface"}},
          .operand = Operand{.metavar = "POINTS", .what = "points file", .destination = &a.points_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int inside_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                  InsideCounts& counts) {
  return answer_query_lines(in, out, err, 3, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const Vec3 point{parsed.value[0], parsed.value[1], parsed.value[2]};  // finite: parse_number_line checks
    const PointLocation location = inside(point, mesh);
    ++counts.by_location[static_cast<int>(location)];
    out << to_string(location) << '\n';
    return std::nullopt;
  });
}

OwnedCommandLine inside_command_line() { return owned_command_line(command_line); }

int run_inside(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  const std::optional<PreparedMesh> loaded = load_mesh_option("inside", arguments.mesh_path, std::cerr);
  if (!loaded) return exit_usage;
  const PreparedMesh& prepared = *loaded;

  const std::string path = arguments.points_path.value_or("-");
  Input points(path);
  if (!check_opened("inside", "points file", path, points)) return exit_usage;
  InsideCounts counts;
  const int status = inside_stream(points.stream(), std::cout, std::cerr, prepared, counts);
  std::ostringstream text;
  text << counts.lines_answered << " points: " << counts.by_location[0] << " outside, " << counts.by_location[1]
       << " inside, " << counts.by_location[2] << " on-surface, " << counts.invalid << " invalid\n";
  return finish_stream_command("inside", points, input_name(path), status, arguments.stats, text.str());
}

}  // namespace raykernel::cli
