// raykernel nearest: the first plane each ray hits (docs/contract.md §4).
#include "commands/plane_nearest.hpp"

#include "commands/commands.hpp"
#include "commands/mesh_nearest.hpp"
#include "commands/sphere_set.hpp"
#include "common/failure.hpp"
#include "common/limits.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_format.hpp"
#include "common/text_input.hpp"

#include <raykernel/nearest_hit.hpp>

#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel nearest --planes FILE [options] [--] [RAYS|-]
       raykernel nearest --mesh FILE [--rule=owned|closed] [options] [--] [RAYS|-]
       raykernel nearest --spheres FILE [options] [--] [RAYS|-]

For each ray, the plane it hits first: among the planes whose relation is hit (t >= 0), the
one with the smallest exact t = ((p - o).n) / (d.n); ties go to the smallest index.

  FILE   one plane per line: px py pz nx ny nz (plane K is the K-th plane line, from 0)
  RAYS   one ray per line: ox oy oz dx dy dz (standard input when RAYS is - or absent)

Numbers in C strtod syntax (decimal, scientific, or hexadecimal with 0x), separated by blanks,
finite when read, and not rounding to zero unless zero (as for classify); blank lines and lines
starting with # are skipped, and so is a UTF-8 byte-order mark at the start of a file. Each ray
line gives one output line:
  hit K T | miss | invalid REASON
where T is the exact t of plane K rounded to the nearest double (ties to even), printed so that
strtod reads it back exactly. Parallel, in-plane and behind planes are never hit. Two t values
are compared exactly, never as rounded doubles: planes whose t differ by less than an ulp are
ordered correctly, and equal t tie.

With --mesh, the triangle it hits first: among the triangles of the mesh in FILE (OBJ, PLY, STL,
OFF or glTF; triangle K counted from 0 in file order, polygons fanned) whose relation under the rule
is hit (raykernel triangle --help), the one with the smallest exact t, ties to the smallest K;
the answer is hit K T or miss. A file that is not a mesh is exit status 2, reported as
raykernel: FILE:LINE: REASON (or FILE: byte N: REASON), with nothing on standard output.
With --mesh a ray line may carry an interval: ox oy oz dx dy dz t_min t_max (0 <= t_min <=
t_max, t_min finite, t_max may be inf); only the triangles whose exact t lies in [t_min, t_max]
count, compared exactly (never a rounded t). Without one the interval is [0, inf].

With --spheres, the sphere it hits first: among the spheres in FILE (one per line: cx cy cz r;
sphere K counted from 0) the one whose smallest root in the ray's interval (with --mesh's ray
lines) is smallest, compared exactly, ties to the smallest K; T is that root rounded to nearest
(raykernel sphere --help). An invalid sphere line is exit status 2, as an invalid plane line.
)";

constexpr const char* help_after = R"(exit status: 0 every ray valid, 1 some ray line invalid, 2 usage or I/O error (an unreadable
file, or standard output that cannot be written: nearest then stops reading) or an invalid
plane or sphere line (reported as raykernel: FILE:N: REASON, with nothing on standard output)
)";

Ray ray_of(const NumberLine& line) {
  const auto& v = line.value;
  return {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
}

// What the command line says.
struct Arguments {
  NearestOptions options;
  std::optional<std::string> planes_path, mesh_path, spheres_path, rays_path;
  std::optional<TriangleRule> rule;
};

CommandLine command_line(Arguments& a) {
  return {.command = "nearest",
          .options = {{"--planes", file(a.planes_path), "the planes (this or --mesh is required)"},
                      {"--mesh", file(a.mesh_path), "a triangle mesh instead of planes"},
                      {"--spheres", file(a.spheres_path),
                       "spheres (lines cx cy cz r) instead of planes; rays may carry t_min t_max"},
                      {"--rule", one_of(a.rule, rule_choices),
                       "with --mesh: which points of a triangle count (default owned)"},
                      {"--path", one_of(a.options.method, method_choices),
                       "which computation answers (default certified; naive is the textbook loop in plain "
                       "doubles, without guarantees)"},
                      {"--exact-t", flag(a.options.exact_t), "append the winner's exact t as P/Q in lowest terms"},
                      {"--hex", flag(a.options.hex), "print T as a hexadecimal float"},
                      {"--stats", flag(a.options.stats), "print to stderr how many decisions each stage made"}},
          .operand = Operand{.metavar = "RAYS", .what = "rays file", .destination = &a.rays_path},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

PlanesFile read_planes(std::istream& in) {
  return read_primitive_file<Plane>(
      in, 6, [](const auto& v) { return Plane{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}}; },
      [](const Plane& plane) { return validate(plane); });
}

int nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, std::span<const Plane> planes,
                   const NearestOptions& options, NearestCounts& counts) {
  LineReader lines(rays);
  std::string line;
  std::string answer;
  while (out && lines.next(line)) {
    const NumberLine parsed = parse_number_line(line, 6);
    if (parsed.status == LineStatus::skip) continue;
    ++counts.lines_answered;

    std::string reason = parsed.reason;
    const Ray ray = ray_of(parsed);
    if (parsed.status == LineStatus::numbers) {
      if (std::optional<std::string> invalid = validate(ray)) reason = *invalid;
    }
    if (!reason.empty()) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), reason);
      continue;
    }

    std::optional<NearestHit> hit;
    switch (options.method) {
      case Method::certified: {
        const TracedNearestHit traced = nearest_hit_traced(ray, planes);
        hit = traced.hit;
        ++counts.relation_stage[static_cast<int>(traced.relation_stage)];
        for (int k = 0; k < stage_count; ++k) counts.comparison_stage[k] += traced.comparisons[static_cast<std::size_t>(k)];
        if (hit) ++counts.t_stage[static_cast<int>(traced.t_stage)];
        break;
      }
      case Method::exact: hit = nearest_hit_exact(ray, planes); break;
      case Method::naive: hit = nearest_hit_naive(ray, planes); break;
    }
    if (!hit) {
      ++counts.misses;
      out << "miss\n";
      continue;
    }
    ++counts.hits;
    answer = hit_answer(hit->plane, hit->t, options.hex);
    if (options.exact_t) {
      const ExactIntersection exact = intersect_exact_rational(ray, planes[hit->plane]);
      answer += ' ';
      answer += exact.t ? exact.t->str() : "none";  // only the naive path can pick a plane with no t
    }
    out << answer << '\n';
  }
  return counts.invalid == 0 ? exit_ok : exit_invalid_line;
}

std::string describe(const NearestCounts& c, Method method) {
  std::ostringstream s;
  s << c.lines_answered << " rays: " << c.hits << " hit, " << c.misses << " miss, " << c.invalid << " invalid\n";
  if (method == Method::certified) {
    s << "relations (slowest stage per ray): " << stage_counts_text(c.relation_stage) << "\n";
    s << "comparisons of two t: " << stage_counts_text(c.comparison_stage) << "\n";
    s << "t of the nearest plane: " << stage_counts_text(c.t_stage) << "\n";
  } else {
    s << no_stages_text(method);
  }
  return s.str();
}

OwnedCommandLine nearest_command_line() { return owned_command_line(command_line); }

int run_nearest(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if ((arguments.planes_path.has_value() + arguments.mesh_path.has_value() + arguments.spheres_path.has_value()) > 1) {
    std::cerr << "raykernel nearest: only one of --planes, --mesh and --spheres can be given\n";
    return exit_usage;
  }
  if (arguments.rule && !arguments.mesh_path) {
    std::cerr << "raykernel nearest: --rule needs --mesh (planes and spheres have no rule)\n";
    return exit_usage;
  }
  const std::string path = arguments.rays_path.value_or("-");
  if (arguments.spheres_path) {
    if (arguments.options.exact_t || arguments.options.method == Method::naive) {
      std::cerr << "raykernel nearest: --exact-t and --path=naive are not for --spheres (raykernel sphere --exact "
                   "prints a root's exact U and V)\n";
      return exit_usage;
    }
    const SphereSetOptions options{.method = arguments.options.method, .hex = arguments.options.hex};
    return run_sphere_nearest(*arguments.spheres_path, path, options, arguments.options.stats);
  }
  if (arguments.mesh_path) {
    const MeshNearestOptions mesh_options{.method = arguments.options.method,
                                          .rule = arguments.rule.value_or(TriangleRule::owned),
                                          .exact_t = arguments.options.exact_t,
                                          .hex = arguments.options.hex,
                                          .stats = arguments.options.stats};
    return run_mesh_nearest(*arguments.mesh_path, path, mesh_options);
  }
  if (!arguments.planes_path) {
    std::cerr << "raykernel nearest: --planes FILE, --mesh FILE or --spheres FILE is required (see raykernel nearest "
                 "--help)\n";
    return exit_usage;
  }

  const std::string& planes_path = *arguments.planes_path;
  PlanesFile planes;
  {
    const Doing doing("reading the planes file " + quote(planes_path, limits::quoted_token_bytes));
    Input planes_input(planes_path, Input::Dash::is_a_file);
    if (!check_opened("nearest", "planes file", planes_path, planes_input)) return exit_usage;
    planes = read_planes(planes_input.stream());
    if (const std::string error = planes_input.read_error(); !error.empty()) {
      std::cerr << "raykernel nearest: I/O error reading planes file '" << printable(planes_path) << "': " << error
                << '\n';
      return exit_usage;
    }
  }
  if (!planes.ok()) {
    std::cerr << "raykernel: " << printable(planes_path) << ":" << planes.error_line << ": " << planes.error << '\n';
    return exit_usage;
  }

  Input rays(path);
  if (!check_opened("nearest", "rays file", path, rays)) return exit_usage;
  NearestCounts counts;
  const int status = nearest_stream(rays.stream(), std::cout, std::cerr, planes.items, arguments.options, counts);
  return finish_stream_command("nearest", rays, input_name(path), status, arguments.options.stats,
                               describe(counts, arguments.options.method));
}

}  // namespace raykernel::cli
