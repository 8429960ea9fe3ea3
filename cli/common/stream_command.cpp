#include "common/stream_command.hpp"

#include "common/text_format.hpp"

#include <iostream>
#include <sstream>

namespace raykernel::cli {

bool parse_method_option(std::string_view command, const std::vector<std::string>& args, std::size_t& i,
                         Method& method) {
  const std::string& a = args[i];
  std::string value;
  if (a.starts_with("--path=")) {
    value = a.substr(7);
  } else if (a == "--path" && i + 1 < args.size()) {
    value = args[++i];
  } else {
    std::cerr << "raykernel " << command << ": --path needs a value: certified, exact or naive\n";
    return false;
  }
  if (value == "certified") method = Method::certified;
  else if (value == "exact") method = Method::exact;
  else if (value == "naive") method = Method::naive;
  else {
    std::cerr << "raykernel " << command << ": unknown path " << quote(value) << " (certified, exact or naive)\n";
    return false;
  }
  return true;
}

Argument argument_kind(const std::string& arg, bool& options_ended) {
  if (options_ended) return Argument::operand;
  if (arg == "--") {
    options_ended = true;
    return Argument::end_of_options;
  }
  return arg.size() > 1 && arg[0] == '-' ? Argument::option : Argument::operand;
}

bool take_single_operand(std::string_view command, std::string_view what, const std::string& operand,
                         std::string& path, bool& given) {
  if (given) {
    std::cerr << "raykernel " << command << ": more than one " << what << " (" << quote(path, path.size()) << ", "
              << quote(operand, operand.size()) << ")\n";
    return false;
  }
  path = operand;
  given = true;
  return true;
}

std::string input_name(const std::string& path) {
  return path.empty() || path == "-" ? "standard input" : "'" + printable(path) + "'";
}

bool check_opened(std::string_view command, std::string_view what, const std::string& path, const Input& input) {
  if (input.is_open()) return true;
  std::cerr << "raykernel " << command << ": cannot open " << what << " '" << printable(path)
            << "': " << input.open_error() << '\n';
  return false;
}

int finish_stream_command(std::string_view command, const Input& input, std::string_view input_name, int status,
                          bool stats, const std::string& stats_text) {
  if (!flush_standard_output()) return exit_usage;
  if (const std::string error = input.read_error(); !error.empty()) {
    std::cerr << "raykernel " << command << ": I/O error reading " << input_name << ": " << error << '\n';
    return exit_usage;
  }
  if (stats) {
    std::istringstream lines(stats_text);
    for (std::string l; std::getline(lines, l);) std::cerr << "raykernel: stats: " << l << '\n';
  }
  return status;
}

std::string no_stages_text(Method method) {
  return std::string("path ") + (method == Method::exact ? "exact" : "naive") + ": no stages\n";
}

bool parse_rule_option(std::string_view command, const std::vector<std::string>& args, std::size_t& i,
                       TriangleRule& rule) {
  const std::string& a = args[i];
  std::string value;
  if (a.starts_with("--rule=")) {
    value = a.substr(7);
  } else if (a == "--rule" && i + 1 < args.size()) {
    value = args[++i];
  } else {
    std::cerr << "raykernel " << command << ": --rule needs a value: owned or closed\n";
    return false;
  }
  if (value == "owned") rule = TriangleRule::owned;
  else if (value == "closed") rule = TriangleRule::closed;
  else {
    std::cerr << "raykernel " << command << ": unknown rule " << quote(value) << " (owned or closed)\n";
    return false;
  }
  return true;
}

std::string stage_counts_text(const std::uint64_t* counts) {
  std::string out;
  for (int k = 0; k < stage_count; ++k) {
    if (k) out += ", ";
    out += std::string(to_string(static_cast<Stage>(k))) + " " + std::to_string(counts[k]);
  }
  return out;
}

void report_invalid_line(std::ostream& out, std::ostream& err, std::uint64_t line_number, const std::string& reason) {
  out << "invalid " << reason << '\n';
  err << "raykernel: line " << line_number << ": " << reason << '\n';
}

}  // namespace raykernel::cli
