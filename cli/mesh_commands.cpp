// raykernel inside and raykernel nearest --mesh (docs/contract.md §7).
#include "failure.hpp"
#include "mesh_commands.hpp"

#include "options.hpp"
#include "text_format.hpp"
#include "text_input.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <iostream>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

constexpr const char* inside_help = R"(usage: raykernel inside --mesh FILE [options] [--] [POINTS|-]

For each point, whether it is inside the closed triangle mesh in FILE (OBJ, PLY, STL or OFF):
  on-surface   the point lies on some triangle (its plane, inside or on its boundary), exactly
  inside       else, the winding number is not 0
  outside      else
The winding number is the signed count of the owned crossings (raykernel triangle --help) of a
ray from the point (along an axis, towards the nearest face of the mesh's bounding box); for a
closed, consistently oriented mesh it is the same for every ray. Everything is decided exactly.

  POINTS  one point per line: x y z (standard input when POINTS is - or absent)

Numbers, blank and # lines, invalid lines and the byte-order mark as for classify; each point
line gives one output line: inside | outside | on-surface | invalid REASON.

options:
  --mesh FILE   the mesh (required; the format from the extension, else from the content)
  --stats       print to stderr how many points were inside, outside and on the surface
  --help        this text
  --            end of options (POINTS may then start with -)

exit status: 0 every point valid, 1 some point line invalid, 2 usage or I/O error or a file
that is not a mesh (reported as raykernel: FILE:LINE: REASON, nothing on standard output)
)";

// `--NAME FILE` or `--NAME=FILE` at args[i] (advancing i past FILE in the first form); false after a message
// when FILE is missing or the option was given before.
bool read_path_option(std::string_view command, std::string_view name, const std::vector<std::string>& args,
                      std::size_t& i, std::string& path, bool& have) {
  const std::string& a = args[i];
  const std::string flag = "--" + std::string(name);
  if (have) {
    std::cerr << "raykernel " << command << ": " << flag << " given twice\n";
    return false;
  }
  if (a == flag) {
    if (i + 1 >= args.size()) {
      std::cerr << "raykernel " << command << ": " << flag << " needs a file\n";
      return false;
    }
    path = args[++i];
  } else {
    path = a.substr(flag.size() + 1);
  }
  have = true;
  return true;
}

}  // namespace

PreparedMesh prepare_mesh(Mesh&& mesh, const std::string& path) {
  const Doing doing("the mesh " + quote(path, limits::quoted_token_bytes) + " and its BVH");
  return PreparedMesh(std::move(mesh));  // valid: the readers return valid meshes
}

std::optional<Mesh> read_mesh_file(const std::string& path, std::ostream& err) {
  const Doing doing("reading the mesh file " + quote(path, limits::quoted_token_bytes));
  try {
    return io::read_mesh(path);
  } catch (const io::mesh_file_error& e) {
    err << "raykernel: " << printable(e.what()) << '\n';
  } catch (const std::bad_alloc&) {
    err << "raykernel: " << printable(path) << ": not enough memory for the mesh\n";
  }
  return std::nullopt;
}

int inside_stream(std::istream& in, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                  InsideCounts& counts) {
  LineReader lines(in);
  std::string line;
  while (out && lines.next(line)) {
    const NumberLine parsed = parse_number_line(line, 3);
    if (parsed.status == LineStatus::skip) continue;
    ++counts.lines_answered;
    if (parsed.status != LineStatus::numbers) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), parsed.reason);
      continue;
    }
    const Vec3 point{parsed.value[0], parsed.value[1], parsed.value[2]};  // finite: parse_number_line checks
    const PointLocation location = inside(point, mesh);
    ++counts.by_location[static_cast<int>(location)];
    out << to_string(location) << '\n';
  }
  return counts.invalid == 0 ? exit_ok : exit_invalid_line;
}

int run_inside(const std::vector<std::string>& args) {
  std::string mesh_path, points_path;
  bool have_mesh = false, have_points = false, options_ended = false, stats = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const Argument kind = argument_kind(a, options_ended);
    if (kind == Argument::end_of_options) continue;
    if (kind == Argument::operand) {
      if (!take_single_operand("inside", "points file", a, points_path, have_points)) return exit_usage;
    } else if (a == "--help" || a == "-h") {
      std::cout << inside_help;
      return finish_standard_output(exit_ok);
    } else if (a == "--stats") {
      stats = true;
    } else if (a == "--mesh" || a.starts_with("--mesh=")) {
      if (!read_path_option("inside", "mesh", args, i, mesh_path, have_mesh)) return exit_usage;
    } else {
      std::cerr << "raykernel inside: unknown option " << quote(a) << " (see raykernel inside --help)\n";
      return exit_usage;
    }
  }
  if (!have_mesh) {
    std::cerr << "raykernel inside: --mesh FILE is required (see raykernel inside --help)\n";
    return exit_usage;
  }
  std::optional<Mesh> mesh = read_mesh_file(mesh_path, std::cerr);
  if (!mesh) return exit_usage;
  const PreparedMesh prepared = prepare_mesh(std::move(*mesh), mesh_path);

  const std::string path = have_points ? points_path : "-";
  Input points(path);
  if (!check_opened("inside", "points file", path, points)) return exit_usage;
  InsideCounts counts;
  const int status = inside_stream(points.stream(), std::cout, std::cerr, prepared, counts);
  std::ostringstream text;
  text << counts.lines_answered << " points: " << counts.by_location[0] << " outside, " << counts.by_location[1]
       << " inside, " << counts.by_location[2] << " on-surface, " << counts.invalid << " invalid\n";
  return finish_stream_command("inside", points, input_name(path), status, stats, text.str());
}

int mesh_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                        const MeshNearestOptions& options, MeshNearestCounts& counts) {
  LineReader lines(rays);
  std::string line, answer;
  while (out && lines.next(line)) {
    const NumberLine parsed = parse_number_line(line, 6);
    if (parsed.status == LineStatus::skip) continue;
    ++counts.lines_answered;
    std::string reason = parsed.reason;
    const auto& v = parsed.value;
    const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (parsed.status == LineStatus::numbers) {
      if (std::optional<std::string> invalid = validate(ray)) reason = *invalid;
    }
    if (!reason.empty()) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), reason);
      continue;
    }
    std::optional<MeshHit> hit;
    switch (options.method) {
      case Method::certified: {
        const TracedMeshHit traced = nearest_hit_traced(ray, mesh, options.rule);
        hit = traced.hit;
        counts.candidates += traced.candidates;
        counts.repeats += traced.repeats;
        counts.ties += traced.ties;
        counts.ties_without_arithmetic += traced.ties_without_arithmetic;
        for (std::size_t k = 0; k < stage_count; ++k) {
          counts.relation_stage[k] += traced.relations[k];
          counts.comparison_stage[k] += traced.comparisons[k];
        }
        break;
      }
      case Method::exact: hit = nearest_hit_exact(ray, mesh.mesh(), options.rule); break;
      case Method::naive: hit = nearest_hit_naive(ray, mesh); break;
    }
    if (!hit) {
      ++counts.misses;
      out << "miss\n";
      continue;
    }
    ++counts.hits;
    answer = "hit ";
    answer += std::to_string(hit->triangle);
    answer += ' ';
    answer += options.hex ? format_hex(hit->intersection.t) : format_shortest(hit->intersection.t);
    if (options.exact_t) {
      const ExactTriangleIntersection exact = intersect_exact_rational(ray, mesh.mesh().triangle(hit->triangle), options.rule);
      answer += ' ';
      answer += exact.t ? exact.t->str() : "none";  // only the naive path can pick a triangle with no t
    }
    out << answer << '\n';
  }
  return counts.invalid == 0 ? exit_ok : exit_invalid_line;
}

int run_mesh_nearest(const std::string& mesh_path, const std::string& rays_path, const MeshNearestOptions& options) {
  std::optional<Mesh> mesh = read_mesh_file(mesh_path, std::cerr);
  if (!mesh) return exit_usage;
  const PreparedMesh prepared = prepare_mesh(std::move(*mesh), mesh_path);
  Input rays(rays_path);
  if (!check_opened("nearest", "rays file", rays_path, rays)) return exit_usage;
  MeshNearestCounts counts;
  const int status = mesh_nearest_stream(rays.stream(), std::cout, std::cerr, prepared, options, counts);
  std::ostringstream text;
  text << counts.lines_answered << " rays: " << counts.hits << " hit, " << counts.misses << " miss, " << counts.invalid
       << " invalid (" << prepared.mesh().triangles.size() << " triangles, rule " << to_string(options.rule) << ")\n";
  if (options.method == Method::certified) {
    text << "candidate triangles: " << counts.candidates << " (relation decided by: " << stage_counts_text(counts.relation_stage)
         << "; repeating the previous candidate " << counts.repeats << ")\n";
    text << "ties of the rounded t: " << counts.ties << " (settled from the vertices " << counts.ties_without_arithmetic
         << "; compared by: " << stage_counts_text(counts.comparison_stage) << ")\n";
  } else {
    text << no_stages_text(options.method);
  }
  return finish_stream_command("nearest", rays, input_name(rays_path), status, options.stats, text.str());
}

}  // namespace raykernel::cli
