// raykernel triangle: one ray–triangle query per line (docs/contract.md §6).
#include "commands/triangle.hpp"

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

constexpr const char* help_before = R"(usage: raykernel triangle [options] [--] [FILE|-]

Intersects one ray with one triangle per input line (standard input when FILE is - or absent):
  ox oy oz dx dy dz ax ay az bx by bz cx cy cz
numbers in C strtod syntax (decimal, scientific, or hexadecimal with 0x), separated by blanks;
a number must be finite when read, and a nonzero number must not round to zero (1e-400 is
invalid, 4e-324 reads as a subnormal and is fine). Blank lines and lines starting with # are
skipped; a UTF-8 byte-order mark at the start is ignored. Each other line gives one output line:
  degenerate | parallel | coplanar | REL LOC T UA UB UC | invalid REASON
REL is hit, behind or miss under the rule; LOC is where the ray's line crosses the triangle's
plane: inside, edge-ab, edge-bc, edge-ca, vertex-a, vertex-b, vertex-c or outside. T is
t = num/den and UA UB UC the barycentric coordinates pi_a/den, pi_b/den, pi_c/den, each the
exact value rounded to the nearest double (ties to even), printed so that strtod reads it back
exactly. (N = (b-a) x (c-a), den = d.N, num = (a-o).N; degenerate: N = 0; parallel,
coplanar: den = 0 with num != 0, num = 0.)
)";

constexpr const char* help_after = R"(exit status: 0 every line valid, 1 some line invalid, 2 usage or I/O error (an unreadable
input, or standard output that cannot be written: triangle then stops reading)
)";

Ray ray_of(const NumberLine& line) {
  const auto& v = line.value;
  return {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
}
Triangle triangle_of(const NumberLine& line) {
  const auto& v = line.value;
  return {{v[6], v[7], v[8]}, {v[9], v[10], v[11]}, {v[12], v[13], v[14]}};
}

bool crosses(TriangleRelation r) {
  return r == TriangleRelation::hit || r == TriangleRelation::behind || r == TriangleRelation::miss;
}


// What the command line says.
struct Arguments {
  TriangleCommandOptions options;
  std::optional<std::string> file;
};

CommandLine command_line(Arguments& a) {
  return {.command = "triangle",
          .options = {{"--rule", one_of(a.options.rule, rule_choices),
                       "owned (default): an edge or vertex hit is counted by exactly one triangle of a closed "
                       "mesh (watertight tie-breaking); closed: the triangle with its boundary"},
                      {"--exact", flag(a.options.exact_t), "append the exact t, UA, UB, UC as P/Q in lowest terms"},
                      {"--path", one_of(a.options.method, method_choices),
                       "which computation answers (default certified; naive is Moller-Trumbore in plain "
                       "doubles with its own closed test, without guarantees; --rule does not apply to it)"},
                      {"--hex", flag(a.options.hex), "print T, UA, UB, UC as hexadecimal floats"},
                      {"--stats", flag(a.options.stats), "print to stderr how many queries each stage decided"}},
          .operand = Operand{.metavar = "FILE", .what = "input file", .destination = &a.file},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int triangle_stream(std::istream& in, std::ostream& out, std::ostream& err, const TriangleCommandOptions& options,
                    TriangleCounts& counts) {
  std::string answer;
  const TriangleOptions query_options{options.rule, true, true};
  return answer_query_lines(in, out, err, 15, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const Ray ray = ray_of(parsed);
    const Triangle triangle = triangle_of(parsed);
    if (std::optional<std::string> invalid = validate(ray, triangle)) return invalid;

    TriangleIntersection result{};
    switch (options.method) {
      case Method::certified: {
        const TracedTriangleIntersection traced = intersect_traced(ray, triangle, query_options);
        result = traced.intersection;
        ++counts.relation_stage[static_cast<int>(traced.relation_stage)];
        if (crosses(result.relation)) ++counts.rounding_stage[static_cast<int>(traced.rounding_stage)];
        break;
      }
      case Method::exact: result = intersect_exact(ray, triangle, query_options); break;
      case Method::naive: result = intersect_naive(ray, triangle); break;
    }
    ++counts.relation[static_cast<int>(result.relation)];
    ++counts.location[static_cast<int>(result.location)];

    answer.assign(to_string(result.relation));
    if (crosses(result.relation)) {
      answer += ' ';
      answer += to_string(result.location);
      for (double x : {result.t, result.barycentric[0], result.barycentric[1], result.barycentric[2]}) {
        answer += ' ';
        answer += options.hex ? format_hex(x) : format_shortest(x);
      }
      if (options.exact_t) {
        const ExactTriangleIntersection exact = intersect_exact_rational(ray, triangle, options.rule);
        if (exact.t && exact.barycentric) {
          for (const Rational* q : {&*exact.t, &(*exact.barycentric)[0], &(*exact.barycentric)[1],
                                    &(*exact.barycentric)[2]}) {
            answer += ' ';
            answer += q->str();
          }
        } else {
          answer += " none none none none";  // only the naive path can disagree with exact
        }
      }
    }
    out << answer << '\n';
    return std::nullopt;
  });
}

std::string describe(const TriangleCounts& c, Method method) {
  std::ostringstream s;
  s << c.lines_answered << " queries:";
  for (int r = 0; r < 6; ++r)
    s << (r ? ", " : " ") << c.relation[r] << ' ' << to_string(static_cast<TriangleRelation>(r));
  s << ", " << c.invalid << " invalid\n";
  s << "locations:";
  for (int l = 0; l < 8; ++l) s << (l ? ", " : " ") << c.location[l] << ' ' << to_string(static_cast<TriangleLocation>(l));
  s << '\n';
  if (method == Method::certified) {
    s << "relation decided by: " << stage_counts_text(c.relation_stage) << "\n";
    s << "t and barycentric coordinates (den != 0) decided by: " << stage_counts_text(c.rounding_stage) << "\n";
  } else {
    s << no_stages_text(method);
  }
  return s.str();
}

OwnedCommandLine triangle_command_line() { return owned_command_line(command_line); }

int run_triangle(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;

  const std::string path = arguments.file.value_or("-");
  Input input(path);
  if (!check_opened("triangle", "file", path, input)) return exit_usage;
  TriangleCounts counts;
  const int status = triangle_stream(input.stream(), std::cout, std::cerr, arguments.options, counts);
  return finish_stream_command("triangle", input, input_name(path), status, arguments.options.stats,
                               describe(counts, arguments.options.method));
}

}  // namespace raykernel::cli
