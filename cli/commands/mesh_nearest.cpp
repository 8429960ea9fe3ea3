// raykernel nearest --mesh: the first triangle of a mesh each ray hits (docs/contract.md §4, §7).
#include "commands/mesh_nearest.hpp"

#include "commands/mesh_file.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <raykernel/occlusion.hpp>

#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel::cli {

int mesh_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const PreparedMesh& mesh,
                        const MeshNearestOptions& options, MeshNearestCounts& counts) {
  LineReader lines(rays);
  std::string line, answer;
  while (out && lines.next(line)) {
    const NumberLineOf parsed_line = parse_ray_line_with_interval(line);  // t_max may be inf
    const NumberLine& parsed = parsed_line.line;
    if (parsed.status == LineStatus::skip) continue;
    ++counts.lines_answered;
    std::string reason = parsed.reason;
    const auto& v = parsed.value;
    const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    RayInterval interval;
    if (parsed.status == LineStatus::numbers) {
      if (parsed_line.count == 8) interval = RayInterval{v[6], v[7]};
      if (std::optional<std::string> invalid = validate(ray)) reason = *invalid;
      else if (std::optional<std::string> bad = validate(interval)) reason = *bad;
    }
    if (!reason.empty()) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), reason);
      continue;
    }
    std::optional<MeshHit> hit;
    switch (options.method) {
      case Method::certified: {
        const TracedMeshHit traced = nearest_hit_traced(ray, interval, mesh, options.rule);
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
      case Method::exact: hit = nearest_hit_exact(ray, interval, mesh.mesh(), options.rule); break;
      case Method::naive: hit = nearest_hit_naive(ray, interval, mesh); break;
    }
    if (!hit) {
      ++counts.misses;
      out << "miss\n";
      continue;
    }
    ++counts.hits;
    answer = hit_answer(hit->triangle, hit->intersection.t, options.hex);
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
  const std::optional<PreparedMesh> loaded = load_prepared_mesh("nearest", mesh_path, std::cerr);
  if (!loaded) return exit_usage;
  const PreparedMesh& prepared = *loaded;
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
    text << "near ties (two t the filter could not order): " << counts.ties << " (settled from the vertices "
         << counts.ties_without_arithmetic
         << "; compared by: " << stage_counts_text(counts.comparison_stage) << ")\n";
  } else {
    text << no_stages_text(options.method);
  }
  return finish_stream_command("nearest", rays, input_name(rays_path), status, options.stats, text.str());
}

}  // namespace raykernel::cli
