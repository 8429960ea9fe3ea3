// raykernel nearest --spheres FILE and raykernel occluded --spheres FILE [--segment] (docs/contract.md §8, §10).
#include "commands/sphere_set.hpp"

#include "common/failure.hpp"
#include "common/limits.hpp"
#include "common/stream_command.hpp"
#include "common/text_format.hpp"
#include "common/text_input.hpp"

#include <raykernel/occlusion.hpp>

#include <iostream>
#include <optional>
#include <sstream>
#include <string>

namespace raykernel::cli {
namespace {

// A ray line of §8 (6 numbers, or 8 with the interval), or a segment line (6 numbers), read and validated: the
// reason it is invalid, or nothing.
struct QueryLine {
  NumberLineOf parsed;
  Ray ray{};
  RayInterval interval{};
  Vec3 p{}, q{};
};

std::optional<std::string> read_query_line(std::string_view line, bool segment, QueryLine& query) {
  query.parsed = segment ? NumberLineOf{parse_number_line(line, 6), 6} : parse_ray_line_with_interval(line);
  const NumberLine& parsed = query.parsed.line;
  if (parsed.status != LineStatus::numbers) return parsed.reason;
  const auto& v = parsed.value;
  query.p = {v[0], v[1], v[2]};
  query.q = {v[3], v[4], v[5]};
  if (segment) return validate_segment(query.p, query.q);
  query.ray = {query.p, query.q};
  query.interval = query.parsed.count == 8 ? RayInterval{v[6], v[7]} : RayInterval{};
  if (std::optional<std::string> reason = validate(query.ray)) return reason;
  return validate(query.interval);
}

// The loop both commands share: every non-skipped line answered by answer(query) (its answer text) or reported.
template <class Answer>
int answer_sphere_lines(std::istream& in, std::ostream& out, std::ostream& err, bool segment, SphereSetCounts& counts,
                        Answer&& answer) {
  LineReader lines(in);
  std::string line;
  QueryLine query;
  while (out && lines.next(line)) {
    const std::optional<std::string> reason = read_query_line(line, segment, query);
    if (query.parsed.line.status == LineStatus::skip) continue;
    ++counts.lines_answered;
    if (reason) {
      ++counts.invalid;
      report_invalid_line(out, err, lines.line_number(), *reason);
      continue;
    }
    out << answer(query) << '\n';
  }
  return counts.invalid == 0 ? exit_ok : exit_invalid_line;
}

// Reads the spheres file at `path` ("-" is a file named "-"); nothing (after a message on stderr) when it cannot be
// opened or read or a line is invalid.
std::optional<SphereSet> load_spheres(std::string_view command, const std::string& path) {
  SpheresFile file;
  {
    const Doing doing("reading the spheres file " + quote(path, limits::quoted_token_bytes));
    Input input(path, Input::Dash::is_a_file);
    if (!check_opened(command, "spheres file", path, input)) return std::nullopt;
    file = read_spheres(input.stream());
    if (const std::string error = input.read_error(); !error.empty()) {
      std::cerr << "raykernel " << command << ": I/O error reading spheres file '" << printable(path) << "': " << error
                << '\n';
      return std::nullopt;
    }
  }
  if (!file.ok()) {
    std::cerr << "raykernel: " << printable(path) << ":" << file.error_line << ": " << file.error << '\n';
    return std::nullopt;
  }
  return SphereSet(file.items);
}

std::string describe(const SphereSetCounts& c, bool nearest, bool segment, std::size_t spheres) {
  std::ostringstream s;
  s << c.lines_answered << (segment ? " segments: " : " rays: ");
  if (nearest) s << c.hits << " hit, " << c.misses << " miss, ";
  else s << c.hits << " occluded, " << c.misses << " clear, ";
  s << c.invalid << " invalid (" << spheres << " spheres)\n";
  return s.str();
}

}  // namespace

SpheresFile read_spheres(std::istream& in) {
  return read_primitive_file<Sphere>(
      in, 4, [](const auto& v) { return Sphere{{v[0], v[1], v[2]}, v[3]}; },
      [](const Sphere& sphere) { return validate(sphere); });
}

int sphere_nearest_stream(std::istream& rays, std::ostream& out, std::ostream& err, const SphereSet& spheres,
                          const SphereSetOptions& options, SphereSetCounts& counts) {
  return answer_sphere_lines(rays, out, err, false, counts, [&](const QueryLine& query) {
    const std::optional<SphereHit> hit =
        options.method == Method::exact ? nearest_hit_exact(query.ray, query.interval, spheres.spheres())
                                        : nearest_hit(query.ray, query.interval, spheres);
    ++(hit ? counts.hits : counts.misses);
    return hit ? hit_answer(hit->sphere, hit->t, options.hex) : std::string("miss");
  });
}

int sphere_occluded_stream(std::istream& lines, std::ostream& out, std::ostream& err, const SphereSet& spheres,
                           const SphereSetOptions& options, SphereSetCounts& counts) {
  return answer_sphere_lines(lines, out, err, options.segment, counts, [&](const QueryLine& query) {
    bool blocked = false;
    if (options.segment) {
      if (options.method == Method::exact) {
        for (const Sphere& sphere : spheres.spheres())
          if ((blocked = segment_meets_exact(query.p, query.q, sphere))) break;
      } else {
        blocked = occluded(query.p, query.q, spheres);
      }
    } else if (options.method == Method::exact) {
      blocked = nearest_hit_exact(query.ray, query.interval, spheres.spheres()).has_value();
    } else {
      blocked = occluded(query.ray, query.interval, spheres);
    }
    ++(blocked ? counts.hits : counts.misses);
    return std::string(blocked ? "occluded" : "clear");
  });
}

int run_sphere_nearest(const std::string& spheres_path, const std::string& rays_path, const SphereSetOptions& options,
                       bool stats) {
  const std::optional<SphereSet> spheres = load_spheres("nearest", spheres_path);
  if (!spheres) return exit_usage;
  Input rays(rays_path);
  if (!check_opened("nearest", "rays file", rays_path, rays)) return exit_usage;
  SphereSetCounts counts;
  const int status = sphere_nearest_stream(rays.stream(), std::cout, std::cerr, *spheres, options, counts);
  return finish_stream_command("nearest", rays, input_name(rays_path), status, stats,
                               describe(counts, true, false, spheres->size()));
}

int run_sphere_occluded(const std::string& spheres_path, const std::string& input_path,
                        const SphereSetOptions& options, bool stats) {
  const std::optional<SphereSet> spheres = load_spheres("occluded", spheres_path);
  if (!spheres) return exit_usage;
  Input input(input_path);
  if (!check_opened("occluded", options.segment ? "segments file" : "rays file", input_path, input)) return exit_usage;
  SphereSetCounts counts;
  const int status = sphere_occluded_stream(input.stream(), std::cout, std::cerr, *spheres, options, counts);
  return finish_stream_command("occluded", input, input_name(input_path), status, stats,
                               describe(counts, false, options.segment, spheres->size()));
}

}  // namespace raykernel::cli
