// raykernel closest: the exact closest point of a mesh to each point (docs/contract.md §11).
#include "commands/mesh_closest.hpp"

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

constexpr const char* help_before = R"(usage: raykernel closest --mesh FILE [options] [--] [POINTS|-]

For each point, the point of the triangle mesh in FILE (OBJ, PLY, STL, OFF or glTF) nearest to it,
by the exact Euclidean distance (triangles closed; a degenerate one is its segment or point; on a
tie of exact distances, the smallest triangle index), decided exactly and rounded once:
  TRIANGLE FEATURE CORNER X Y Z D2 DISTANCE D2_EXACT
  TRIANGLE  the triangle's index in the file (counted from 0)
  FEATURE   vertex, edge or face: where on the triangle the point lies
  CORNER    vertex: 0, 1, 2 for its vertices a, b, c; edge: 0, 1, 2 for ab, bc, ca; face: 0
  X Y Z     the exact closest point, each coordinate rounded to nearest (ties to even)
  D2        the exact squared distance rounded to nearest (inf beyond the doubles)
  DISTANCE  the square root of the exact squared distance, rounded once to nearest
  D2_EXACT  the exact squared distance as a fraction N/D in lowest terms
With --signed, a SIGNED column after DISTANCE: -DISTANCE inside the mesh, DISTANCE outside, 0 on
it (the exact inside, raykernel inside --help; meaningful for a closed mesh).
Numbers are printed as the shortest decimals that read back as the same doubles.

  POINTS  one point per line: x y z (standard input when POINTS is - or absent)

Numbers, blank and # lines, invalid lines and the byte-order mark as for classify; each point
line gives one output line, or: invalid REASON.
)";

constexpr const char* help_after = R"(exit status: 0 every point valid, 1 some point line invalid, 2 usage or I/O error or a file
that is not a mesh or has no triangles (reported as raykernel: FILE:LINE: REASON, nothing on
standard output)
)";

struct Arguments {
  std::optional<std::string> mesh_path, points_path;
  bool with_sign = false;
  bool stats = false;
};

CommandLine command_line(Arguments& a) {
  return {.command = "closest",
          .options = {{"--mesh", file(a.mesh_path),
                       "the mesh (required; the format from the extension, else from the content)"},
                      {"--signed", flag(a.with_sign), "add the signed distance (negative inside)"},
                      {"--stats", flag(a.stats), "print to stderr how many closest points were vertices, edges, faces"}},
          .operand = Operand{.metavar = "POINTS", .what = "points file", .destination = &a.points_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int closest_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh, bool with_sign,
                   ClosestCounts& counts) {
  return answer_query_lines(in, out, err, 3, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const Vec3 point{parsed.value[0], parsed.value[1], parsed.value[2]};  // finite: parse_number_line checks
    const ClosestPoint c = closest_point(point, mesh);
    ++counts.by_feature[static_cast<int>(c.feature)];
    out << c.triangle << ' ' << to_string(c.feature) << ' ' << static_cast<int>(c.corner) << ' '
        << format_shortest(c.point.x) << ' ' << format_shortest(c.point.y) << ' ' << format_shortest(c.point.z) << ' '
        << format_shortest(c.squared_distance) << ' ' << format_shortest(c.distance);
    if (with_sign) out << ' ' << format_shortest(signed_distance(point, mesh, c));
    out << ' ' << c.squared_distance_exact.str() << '\n';
    return std::nullopt;
  });
}

OwnedCommandLine closest_command_line() { return owned_command_line(command_line); }

int run_closest(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  const std::optional<PreparedMesh> loaded = load_mesh_option("closest", arguments.mesh_path, std::cerr);
  if (!loaded) return exit_usage;
  const PreparedMesh& prepared = *loaded;
  if (prepared.mesh().triangles.empty()) {
    std::cerr << "raykernel: closest: " << *arguments.mesh_path << ": the mesh has no triangles\n";
    return exit_usage;
  }
  const std::string path = arguments.points_path.value_or("-");
  Input points(path);
  if (!check_opened("closest", "points file", path, points)) return exit_usage;
  ClosestCounts counts;
  const int status = closest_stream(points.stream(), std::cout, std::cerr, prepared, arguments.with_sign, counts);
  std::ostringstream text;
  text << counts.lines_answered << " points: " << counts.by_feature[0] << " at a vertex, " << counts.by_feature[1]
       << " on an edge, " << counts.by_feature[2] << " on a face, " << counts.invalid << " invalid\n";
  return finish_stream_command("closest", points, input_name(path), status, arguments.stats, text.str());
}

}  // namespace raykernel::cli
