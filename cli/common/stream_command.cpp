#include "common/stream_command.hpp"

#include "common/text_format.hpp"

#include <iostream>
#include <sstream>

namespace raykernel::cli {

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
