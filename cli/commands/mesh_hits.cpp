// raykernel hits --mesh: every triangle each ray hits within its interval, and the signed count of its owned
// crossings (docs/contract.md §8; the output format is decided in docs/contract.md).
#include "commands/commands.hpp"
#include "commands/mesh_file.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <raykernel/occlusion.hpp>

#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel hits --mesh FILE [options] [--] [RAYS|-]

For each ray, every triangle of the mesh in FILE (OBJ, PLY, STL, OFF or glTF) whose relation under the rule
is hit (raykernel triangle --help) at an exact t within the ray's interval, each triangle once, ordered
by exact t (ties by triangle index), and the signed count of the owned crossings there (+1 where the
ray enters a triangle through its front, d.N > 0, -1 through its back; owned whatever the rule).

  RAYS   one ray per line: ox oy oz dx dy dz, or ox oy oz dx dy dz t_min t_max
         (0 <= t_min <= t_max, t_min finite, t_max may be inf; without them [0, inf])

Numbers, blank and # lines, invalid lines and the byte-order mark as for classify; each ray line gives
one output line:
  hits N crossings C K1 T1 K2 T2 ... | invalid REASON
with N the number of triangles hit, C the signed count, and each K T a triangle and its t rounded to
the nearest double (printed so that strtod reads it back exactly).
)";

constexpr const char* help_after = R"(exit status: 0 every ray valid, 1 some ray line invalid, 2 usage or I/O error or a file that is
not a mesh (reported as raykernel: FILE:LINE: REASON, nothing on standard output)
)";

struct Arguments {
  std::optional<std::string> mesh_path, rays_path;
  TriangleRule rule = TriangleRule::owned;
  bool exact = false;
  bool hex = false;
  bool stats = false;
};

const Choices<bool> hits_path_choices = {{"certified", false}, {"exact", true}};

CommandLine command_line(Arguments& a) {
  return {.command = "hits",
          .options = {{"--mesh", file(a.mesh_path),
                       "the mesh (required; the format from the extension, else from the content)"},
                      {"--rule", one_of(a.rule, rule_choices), "which points of a triangle count (default owned)"},
                      {"--path", one_of(a.exact, hits_path_choices),
                       "which computation answers (default certified; exact: every triangle in rationals)"},
                      {"--hex", flag(a.hex), "print each T as a hexadecimal float"},
                      {"--stats", flag(a.stats), "print to stderr how many rays and hits there were"}},
          .operand = Operand{.metavar = "RAYS", .what = "rays file", .destination = &a.rays_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

OwnedCommandLine hits_command_line() { return owned_command_line(command_line); }

int run_hits(const std::vector<std::string>& args) {
  Arguments a;
  if (const std::optional<int> status = parse_command_line(command_line(a), args)) return *status;
  const std::optional<PreparedMesh> loaded = load_mesh_option("hits", a.mesh_path, std::cerr);
  if (!loaded) return exit_usage;
  const PreparedMesh& prepared = *loaded;
  const std::string path = a.rays_path.value_or("-");
  Input rays(path);
  if (!check_opened("hits", "rays file", path, rays)) return exit_usage;
  std::uint64_t lines_answered = 0, invalid = 0, hit_count = 0;
  LineReader lines(rays.stream());
  std::string line, answer;
  while (std::cout && lines.next(line)) {
    const NumberLineOf parsed_line = parse_ray_line_with_interval(line);
    const NumberLine& parsed = parsed_line.line;
    if (parsed.status == LineStatus::skip) continue;
    ++lines_answered;
    std::optional<std::string> reason;
    if (parsed.status != LineStatus::numbers) reason = parsed.reason;
    const auto& v = parsed.value;
    const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    const RayInterval interval = parsed_line.count == 8 ? RayInterval{v[6], v[7]} : RayInterval{};
    if (!reason) reason = validate(ray);
    if (!reason) reason = validate(interval);
    if (reason) {
      ++invalid;
      report_invalid_line(std::cout, std::cerr, lines.line_number(), *reason);
      continue;
    }
    const MeshHits h = a.exact ? all_hits_exact(ray, interval, prepared.mesh(), a.rule)
                               : all_hits(ray, interval, prepared, a.rule);
    hit_count += h.hits.size();
    answer = "hits " + std::to_string(h.hits.size()) + " crossings " + std::to_string(h.crossings);
    for (const MeshHit& x : h.hits) {
      answer += ' ';
      answer += std::to_string(x.triangle);
      answer += ' ';
      answer += a.hex ? format_hex(x.intersection.t) : format_shortest(x.intersection.t);
    }
    std::cout << answer << '\n';
  }
  std::ostringstream text;
  text << lines_answered << " rays: " << hit_count << " hits, " << invalid << " invalid ("
       << prepared.mesh().triangles.size() << " triangles, rule " << to_string(a.rule) << ")\n";
  return finish_stream_command("hits", rays, input_name(path), invalid == 0 ? exit_ok : exit_invalid_line, a.stats,
                               text.str());
}

}  // namespace raykernel::cli
