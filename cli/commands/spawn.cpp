// raykernel spawn: the origin of a secondary ray that never re-hits its surface (docs/contract.md §9).
#include "commands/spawn.hpp"

#include "commands/commands.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <charconv>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel spawn [options] [--] [FILE|-]

The origin of a new ray (reflected, refracted, or a shadow ray) leaving a hit point on a triangle,
one query per input line (standard input when FILE is - or absent):
  ox oy oz dx dy dz ax ay az bx by bz cx cy cz wx wy wz
The hit point P is where the ray o + t d crosses the plane of the triangle a b c, exactly (any
sign of t, inside the triangle or not); w is the new ray's direction. With N = (b-a) x (c-a), the
new ray leaves towards s = sign(w.N). The answer is P rounded to the nearest double, coordinate by
coordinate, when that point is strictly on side s; otherwise the coordinate of the largest |N_i|
moved k steps (through consecutive doubles) until it is, for the smallest k. So the new ray never
hits the triangle it leaves. Numbers as for classify; blank and # lines skipped. Output per line:
  X Y Z K | invalid REASON
X Y Z printed so that they read back exactly, K an exact integer (it may exceed 2^53).

With --sphere, the new ray leaves a sphere: lines of 10 numbers
  px py pz cx cy cz r wx wy wz
p is the hit point as the renderer holds it (it need not lie on the sphere), w the new direction,
N = p - c, s = sign(w.N) (outward +1, inward -1). The origin is p when it is strictly outside with
w.(p - c) >= 0 (outward) or strictly inside (inward); otherwise the coordinate of the largest |N_i|
(outward: among the axes with w_i N_i > 0) moved the fewest steps until it is. Leaving outward the
new ray never meets the sphere; leaving inward it meets it once, where it leaves.
)";

constexpr const char* help_after = R"(Invalid lines: a non-finite number, a zero d or w, a degenerate triangle (N = 0), a ray parallel
to the plane, w parallel to the plane, (--to) q in the plane, a rounded point that overflows, or no
representable origin on the side; (--sphere) a radius not positive, p = c, or w tangent at p.

exit status: 0 every line valid, 1 some line invalid, 2 usage or I/O error
)";

struct Arguments {
  SpawnCommandOptions options;
  bool binary32 = false;
  std::optional<std::string> file;
};

CommandLine command_line(Arguments& a) {
  return {.command = "spawn",
          .options = {{"--float", flag(a.binary32),
                       "the origin in binary32 (P rounded straight to float, steps through floats), printed "
                       "as the shortest decimal that reads back to that float"},
                      {"--point", flag(a.options.point),
                       "the hit point is given as a point: lines of 15 numbers px py pz ax ... cz wx wy wz"},
                      {"--to", flag(a.options.to),
                       "a target point q in place of w (a shadow ray towards q; s = sign((q-a).N)): the "
                       "segment from the origin to q never meets the triangle"},
                      {"--sphere", flag(a.options.sphere),
                       "leaving a sphere: lines of 10 numbers px py pz cx cy cz r wx wy wz (not with --point or "
                       "--to)"}},
          .operand = Operand{.metavar = "FILE", .what = "input file", .destination = &a.file},
          .help_before = help_before,
          .help_after = help_after};
}

std::string format_in(double x, OriginFormat format) {
  if (format == OriginFormat::binary64) return format_shortest(x);
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(x));  // exact: x is a float
  return std::string(buf, r.ptr);
}

}  // namespace

int spawn_stream(std::istream& in, std::ostream& out, std::ostream& err, const SpawnCommandOptions& options,
                 SpawnCounts& counts) {
  const int t = options.point ? 3 : 6;  // where the triangle starts
  const int numbers = options.sphere ? 10 : options.point ? 15 : 18;
  return answer_query_lines(in, out, err, numbers, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const auto& v = parsed.value;
    const auto vec = [&](int k) { return Vec3{v[k], v[k + 1], v[k + 2]}; };
    const auto answer = [&]() -> SpawnedOrigin {
      if (options.sphere) return spawn(vec(0), Sphere{vec(3), v[6]}, vec(7), options.format);
      const HitPoint hit = options.point ? HitPoint::at(vec(0)) : HitPoint::crossing({vec(0), vec(3)});
      const Triangle triangle{vec(t), vec(t + 3), vec(t + 6)};
      return options.to ? spawn_to(hit, triangle, vec(t + 9), options.format)
                        : spawn(hit, triangle, vec(t + 9), options.format);
    };
    try {
      const SpawnedOrigin o = answer();
      if (o.steps != 0) ++counts.moved;
      out << format_in(o.origin.x, options.format) << ' ' << format_in(o.origin.y, options.format) << ' '
          << format_in(o.origin.z, options.format) << ' ' << o.steps << '\n';
      return std::nullopt;
    } catch (const invalid_input& e) {
      return e.what();
    }
  });
}

OwnedCommandLine spawn_command_line() { return owned_command_line(command_line); }

int run_spawn(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;
  if (arguments.options.sphere && (arguments.options.point || arguments.options.to)) {
    std::cerr << "raykernel spawn: --sphere takes the point on every line; --point and --to are for triangles\n";
    return exit_usage;
  }
  if (arguments.binary32) arguments.options.format = OriginFormat::binary32;
  const std::string path = arguments.file.value_or("-");
  Input input(path);
  if (!check_opened("spawn", "file", path, input)) return exit_usage;
  SpawnCounts counts;
  const int status = spawn_stream(input.stream(), std::cout, std::cerr, arguments.options, counts);
  std::ostringstream text;
  text << counts.lines_answered << " lines: " << counts.invalid << " invalid, " << counts.moved
       << " origins moved off the rounded hit point (k >= 1)\n";
  return finish_stream_command("spawn", input, input_name(path), status, false, text.str());
}

}  // namespace raykernel::cli
