// raykernel sphere: one ray–sphere query per line (docs/contract.md §10).
#include "commands/sphere.hpp"

#include "commands/commands.hpp"
#include "common/options.hpp"
#include "common/stream_command.hpp"
#include "common/text_input.hpp"

#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace raykernel::cli {
namespace {

constexpr const char* help_before = R"(usage: raykernel sphere [options] [--] [FILE|-]

Intersects one ray with one sphere per input line (standard input when FILE is - or absent):
  ox oy oz dx dy dz cx cy cz r
numbers in C strtod syntax (decimal, scientific, or hexadecimal with 0x), separated by blanks;
a number must be finite when read, and a nonzero number must not round to zero (1e-400 is
invalid, 4e-324 reads as a subnormal and is fine). Blank lines and lines starting with # are
skipped; a UTF-8 byte-order mark at the start is ignored. Each other line gives one output line:
  ORIGIN miss | ORIGIN tangent T0 | ORIGIN cross T1 T2 | invalid REASON
ORIGIN is inside, on-surface or outside (the sign of C = |o-c|^2 - r^2). With f = o - c,
A = d.d, B = d.f, D = B^2 - A.C: miss when D < 0, tangent (t0 = -B/A) when D = 0, cross
(t1 = (-B - sqrt D)/A < t2 = (-B + sqrt D)/A) when D > 0. Each root is the exact value
rounded to the nearest double (ties to even), printed so that strtod reads it back exactly.
)";

constexpr const char* help_after = R"(exit status: 0 every line valid, 1 some line invalid, 2 usage or I/O error (an unreadable
input, or standard output that cannot be written: sphere then stops reading)
)";

struct Arguments {
  SphereCommandOptions options;
  std::optional<std::string> file;
};

CommandLine command_line(Arguments& a) {
  return {.command = "sphere",
          .options = {{"--exact", flag(a.options.exact),
                       "append the exact roots as U V, P/Q in lowest terms: the roots are U -/+ sqrt(V) "
                       "(U = -B/A, V = D/A^2; V = 0 for tangent, nothing for miss)"},
                      {"--path", one_of(a.options.method, method_choices),
                       "which computation answers (default certified; naive is the textbook quadratic formula "
                       "in plain doubles, without guarantees)"},
                      {"--hex", flag(a.options.hex), "print the roots as hexadecimal floats"},
                      {"--stats", flag(a.options.stats), "print to stderr how many queries each stage decided"}},
          .operand = Operand{.metavar = "FILE", .what = "input file", .destination = &a.file},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int sphere_stream(std::istream& in, std::ostream& out, std::ostream& err, const SphereCommandOptions& options,
                  SphereCounts& counts) {
  std::string answer;
  return answer_query_lines(in, out, err, 10, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const auto& v = parsed.value;
    const Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    const Sphere sphere{{v[6], v[7], v[8]}, v[9]};
    if (std::optional<std::string> invalid = validate(ray, sphere)) return invalid;

    SphereIntersection result{};
    switch (options.method) {
      case Method::certified: {
        const TracedSphereIntersection traced = intersect_traced(ray, sphere);
        result = traced.intersection;
        ++counts.relation_stage[static_cast<int>(traced.relation_stage)];
        if (result.relation != SphereRelation::miss) ++counts.rounding_stage[static_cast<int>(traced.rounding_stage)];
        break;
      }
      case Method::exact: result = intersect_exact(ray, sphere); break;
      case Method::naive: result = intersect_naive(ray, sphere); break;
    }
    ++counts.origin[static_cast<int>(result.origin)];
    ++counts.relation[static_cast<int>(result.relation)];

    answer.assign(to_string(result.origin));
    answer += ' ';
    answer += to_string(result.relation);
    auto root = [&](double t) {
      answer += ' ';
      answer += options.hex ? format_hex(t) : format_shortest(t);
    };
    if (result.relation != SphereRelation::miss) root(result.t1);
    if (result.relation == SphereRelation::cross) root(result.t2);
    if (options.exact) {
      const ExactSphereIntersection exact = intersect_exact_rational(ray, sphere);
      if (exact.relation != result.relation) {
        answer += " none none";  // only the naive path can disagree with exact
      } else if (exact.u && exact.v) {
        answer += ' ';
        answer += exact.u->str();
        answer += ' ';
        answer += exact.v->str();
      }
    }
    out << answer << '\n';
    return std::nullopt;
  });
}

std::string describe(const SphereCounts& c, Method method) {
  std::ostringstream s;
  s << c.lines_answered << " queries:";
  for (int r = 0; r < 3; ++r) s << (r ? ", " : " ") << c.relation[r] << ' ' << to_string(static_cast<SphereRelation>(r));
  s << ", " << c.invalid << " invalid\n";
  s << "origins:";
  for (int o = 0; o < 3; ++o) s << (o ? ", " : " ") << c.origin[o] << ' ' << to_string(static_cast<SphereOrigin>(o));
  s << '\n';
  if (method == Method::certified) {
    s << "relation decided by: " << stage_counts_text(c.relation_stage) << "\n";
    s << "roots (tangent, cross) decided by: " << stage_counts_text(c.rounding_stage) << "\n";
  } else {
    s << no_stages_text(method);
  }
  return s.str();
}

OwnedCommandLine sphere_command_line() { return owned_command_line(command_line); }

int run_sphere(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;

  const std::string path = arguments.file.value_or("-");
  Input input(path);
  if (!check_opened("sphere", "file", path, input)) return exit_usage;
  SphereCounts counts;
  const int status = sphere_stream(input.stream(), std::cout, std::cerr, arguments.options, counts);
  return finish_stream_command("sphere", input, input_name(path), status, arguments.options.stats,
                               describe(counts, arguments.options.method));
}

}  // namespace raykernel::cli
