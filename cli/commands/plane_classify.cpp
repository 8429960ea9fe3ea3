// raykernel classify: one ray–plane query per line (docs/contract.md §3).
#include "commands/plane_classify.hpp"

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

constexpr const char* help_before = R"(usage: raykernel classify [options] [--] [FILE|-]

Classifies one ray-plane query per input line (standard input when FILE is - or absent):
  ox oy oz dx dy dz px py pz nx ny nz
numbers in C strtod syntax (decimal, scientific, or hexadecimal with 0x), separated by blanks;
a number must be finite when read, and a nonzero number must not round to zero (1e-400 is
invalid, 4e-324 reads as a subnormal and is fine). Blank lines and lines starting with # are
skipped; a UTF-8 byte-order mark at the start is ignored. Each other line gives one output line:
  hit T | behind T | parallel | in-plane | invalid REASON
where T is t = ((p - o).n) / (d.n) rounded to the nearest double (ties to even), printed so
that strtod reads it back exactly.
)";

constexpr const char* help_after = R"(exit status: 0 every line valid, 1 some line invalid, 2 usage or I/O error (an unreadable
input, or standard output that cannot be written: classify then stops reading)
)";

Ray ray_of(const NumberLine& line) {
  const auto& v = line.value;
  return {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
}
Plane plane_of(const NumberLine& line) {
  const auto& v = line.value;
  return {{v[6], v[7], v[8]}, {v[9], v[10], v[11]}};
}

// What the command line says.
struct Arguments {
  ClassifyOptions options;
  std::optional<std::string> file;
};

CommandLine command_line(Arguments& a) {
  return {.command = "classify",
          .options = {{"--path", one_of(a.options.method, method_choices),
                       "which computation answers (default certified; naive is the textbook formula in plain "
                       "doubles, without guarantees)"},
                      {"--exact-t", flag(a.options.exact_t), "append the exact t as P/Q in lowest terms"},
                      {"--hex", flag(a.options.hex), "print T as a hexadecimal float"},
                      {"--stats", flag(a.options.stats), "print to stderr how many queries each stage decided"}},
          .operand = Operand{.metavar = "FILE", .what = "input file", .destination = &a.file},
          .help_before = help_before,
          .help_after = help_after};
}

}  // namespace

int classify_stream(std::istream& in, std::ostream& out, std::ostream& err, const ClassifyOptions& options,
                    ClassifyCounts& counts) {
  std::string answer;
  return answer_query_lines(in, out, err, 12, counts.lines_answered, counts.invalid,
                            [&](const NumberLine& parsed) -> std::optional<std::string> {
    const Ray ray = ray_of(parsed);
    const Plane plane = plane_of(parsed);
    if (std::optional<std::string> invalid = validate(ray, plane)) return invalid;

    Intersection result{};
    switch (options.method) {
      case Method::certified: {
        const TracedIntersection traced = intersect_traced(ray, plane);
        result = traced.intersection;
        ++counts.relation_stage[static_cast<int>(traced.relation_stage)];
        if (result.relation == Relation::hit || result.relation == Relation::behind)
          ++counts.t_stage[static_cast<int>(traced.t_stage)];
        break;
      }
      case Method::exact: result = intersect_exact(ray, plane); break;
      case Method::naive: result = intersect_naive(ray, plane); break;
    }
    ++counts.relation[static_cast<int>(result.relation)];

    answer.assign(to_string(result.relation));
    if (result.relation == Relation::hit || result.relation == Relation::behind) {
      answer += ' ';
      answer += options.hex ? format_hex(result.t) : format_shortest(result.t);
      if (options.exact_t) {
        const ExactIntersection exact = intersect_exact_rational(ray, plane);
        answer += ' ';
        answer += exact.t ? exact.t->str() : "none";  // only the naive path can disagree with exact
      }
    }
    out << answer << '\n';
    return std::nullopt;
  });
}

std::string describe(const ClassifyCounts& c, Method method) {
  std::ostringstream s;
  s << c.lines_answered << " queries: " << c.relation[0] << " hit, " << c.relation[1] << " behind, "
    << c.relation[2] << " parallel, " << c.relation[3] << " in-plane, " << c.invalid << " invalid\n";
  if (method == Method::certified) {
    s << "relation decided by: " << stage_counts_text(c.relation_stage) << "\n";
    s << "t (hit, behind) decided by: " << stage_counts_text(c.t_stage) << "\n";
  } else {
    s << no_stages_text(method);
  }
  return s.str();
}

OwnedCommandLine classify_command_line() { return owned_command_line(command_line); }

int run_classify(const std::vector<std::string>& args) {
  Arguments arguments;
  if (const std::optional<int> status = parse_command_line(command_line(arguments), args)) return *status;

  const std::string path = arguments.file.value_or("-");
  Input input(path);
  if (!check_opened("classify", "file", path, input)) return exit_usage;
  ClassifyCounts counts;
  const int status = classify_stream(input.stream(), std::cout, std::cerr, arguments.options, counts);
  return finish_stream_command("classify", input, input_name(path), status, arguments.options.stats,
                               describe(counts, arguments.options.method));
}

}  // namespace raykernel::cli
