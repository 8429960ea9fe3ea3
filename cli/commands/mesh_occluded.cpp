// raykernel occluded: whether anything blocks each ray in its interval, or each open segment (docs/contract.md §8).
#include "commands/mesh_occluded.hpp"

#include "commands/commands.hpp"
#include "commands/mesh_file.hpp"
#include "commands/sphere_set.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel occluded --mesh FILE [options] [--] [RAYS|-]
       raykernel occluded --segment --mesh FILE [options] [--] [SEGMENTS|-]
       raykernel occluded [--segment] --spheres FILE [options] [--] [RAYS|SEGMENTS|-]

For each ray, whether some triangle of the mesh in FILE (OBJ, PLY, STL, OFF or glTF) blocks it within its
interval: a triangle whose relation under the rule is hit (raykernel triangle --help) at an exact t
with t_min <= t <= t_max, compared exactly (never a rounded t). With --segment, for each pair of
points p, q, whether some triangle meets the open segment between them (0 < t < 1 along the exact
direction q - p, which is not rounded; the endpoints never count). Coplanar and degenerate triangles
never block. Under the owned rule (the default) a ray or segment through a shared edge or vertex
of a closed mesh is blocked by exactly one triangle around it: it never leaks through.
With --spheres, the spheres in FILE (one per line: cx cy cz r) instead of a mesh: a sphere is
closed and blocks when one of its roots (a tangent root included) lies in the ray's interval, or
strictly inside the open segment.

  RAYS      one ray per line: ox oy oz dx dy dz, or ox oy oz dx dy dz t_min t_max
            (0 <= t_min <= t_max, t_min finite, t_max may be inf; without them [0, inf])
  SEGMENTS  one segment per line: px py pz qx qy qz (p and q different)

Numbers, blank and # lines, invalid lines and the byte-order mark as for classify; each line gives
one output line: occluded | clear | invalid REASON.
)";

constexpr const char* help_after = R"(exit status: 0 every line valid, 1 some line invalid, 2 usage or I/O error or a file that is
not a mesh (reported as raykernel: FILE:LINE: REASON, nothing on standard output)
)";

// What the command line says.
struct Arguments {
  MeshOccludedOptions options;
  std::optional<std::string> mesh_path, spheres_path, input_path;
  std::optional<TriangleRule> rule;
  bool stats = false;
};

const Choices<Method> occluded_method_choices = {{"certified", Method::certified}, {"exact", Method::exact}};

CommandLine command_line(Arguments& a) {
  return {.command = "occluded",
          .options = {{"--mesh", file(a.mesh_path),
                       "the mesh (this or --spheres is required; the format from the extension, else from the "
                       "content)"},
                      {"--spheres", file(a.spheres_path), "spheres (lines cx cy cz r) instead of a mesh"},
                      {"--segment", flag(a.options.segment), "lines of two points p q: the open segment between them"},
                      {"--rule", one_of(a.rule, rule_choices),
                       "with --mesh: which points of a triangle count (default owned)"},
                      {"--path", one_of(a.options.method, occluded_method_choices),
                       "which computation answers (default certified; exact: every triangle in rationals)"},
                      {"--stats", flag(a.stats), "print to stderr how many lines were occluded and clear"}},
          .operand = Operand{.metavar = "RAYS", .what = "input file", .destination = &a.input_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int mesh_occluded_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                         const MeshOccludedOptions& options, MeshOccludedCounts& counts) {
  LineReader lines(in);
  std::string line;
  while (out && lines.next(line)) {
    const NumberLineOf parsed_line =
        options.segment ? NumberLineOf{parse_number_line(line, 6), 6} : parse_ray_line_with_interval(line);
    const NumberLine& parsed = parsed_line.line;
    if (parsed.status == LineStatus::skip) continue;
    ++counts.lines_answered;
    std::optional<std::string> reason;
    if (parsed.status != LineStatus::numbers) reason = parsed.reason;
    const auto& v = parsed.value;
    const Vec3 first{v[0], v[1], v[2]}, second{v[3], v[4], v[5]};
    bool blocked = false;
    if (!reason && options.segment) {
      reason = validate_segment(first, second);
      if (!reason)
        blocked = options.method == Method::exact ? occluded_exact(first, second, mesh.mesh(), options.rule)
                                                  : occluded(first, second, mesh, options.rule);
    } else if (!reason) {
      const Ray ray{first, second};
      const RayInterval interval = parsed_line.count == 8 ? RayInterval{v[6], v[7]} : RayInterval{};
      reason = validate(ray);
      if (!reason) reason = validate(interval);
      if (!reason)
        blocked = options.method == Method::exact ? occluded_exact(ray, interval, mesh.mesh(), options.rule)
                                                  : occluded(ray, interval, mesh, options.rule);
    }
    if (reason) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), *reason);
      continue;
    }
    ++(blocked ? counts.occluded : counts.clear);
    out << (blocked ? "occluded\n" : "clear\n");
  }
  return counts.invalid == 0 ? exit_ok : exit_invalid_line;
}

OwnedCommandLine occluded_command_line() { return owned_command_line(command_line); }

int run_occluded(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if (arguments.spheres_path) {
    if (arguments.mesh_path) {
      std::cerr << "raykernel occluded: --mesh and --spheres cannot be given together\n";
      return exit_usage;
    }
    if (arguments.rule) {
      std::cerr << "raykernel occluded: --rule needs --mesh (spheres have no rule)\n";
      return exit_usage;
    }
    const SphereSetOptions options{.method = arguments.options.method, .segment = arguments.options.segment};
    return run_sphere_occluded(*arguments.spheres_path, arguments.input_path.value_or("-"), options, arguments.stats);
  }
  arguments.options.rule = arguments.rule.value_or(TriangleRule::owned);
  const std::optional<PreparedMesh> loaded = load_mesh_option("occluded", arguments.mesh_path, std::cerr);
  if (!loaded) return exit_usage;
  const PreparedMesh& prepared = *loaded;

  const std::string path = arguments.input_path.value_or("-");
  Input input(path);
  if (!check_opened("occluded", arguments.options.segment ? "segments file" : "rays file", path, input))
    return exit_usage;
  MeshOccludedCounts counts;
  const int status = mesh_occluded_stream(input.stream(), std::cout, std::cerr, prepared, arguments.options, counts);
  std::ostringstream text;
  text << counts.lines_answered << (arguments.options.segment ? " segments: " : " rays: ") << counts.occluded
       << " occluded, " << counts.clear << " clear, " << counts.invalid << " invalid ("
       << prepared.mesh().triangles.size() << " triangles, rule " << to_string(arguments.options.rule) << ")\n";
  return finish_stream_command("occluded", input, input_name(path), status, arguments.stats, text.str());
}

}  // namespace raykernel::cli
