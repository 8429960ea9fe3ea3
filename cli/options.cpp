#include "options.hpp"

#include <iostream>
#include <sstream>

namespace raykernel::cli {

bool parse_path_option(std::string_view command, const std::vector<std::string>& args, std::size_t& i, Path& path) {
  const std::string& a = args[i];
  std::string value;
  if (a.size() > 6 && a[6] == '=') {
    value = a.substr(7);
  } else if (a == "--path" && i + 1 < args.size()) {
    value = args[++i];
  } else {
    std::cerr << "raykernel " << command << ": --path needs a value: certified, exact or naive\n";
    return false;
  }
  if (value == "certified") path = Path::certified;
  else if (value == "exact") path = Path::exact;
  else if (value == "naive") path = Path::naive;
  else {
    std::cerr << "raykernel " << command << ": unknown path '" << value << "' (certified, exact or naive)\n";
    return false;
  }
  return true;
}

std::istream* open_input(std::string_view command, std::string_view what, const std::string& path,
                         std::ifstream& storage) {
  if (path.empty() || path == "-") return &std::cin;
  storage.open(path, std::ios::binary);
  if (!storage) {
    std::cerr << "raykernel " << command << ": cannot open " << what << " '" << path << "'\n";
    return nullptr;
  }
  return &storage;
}

int finish_stream_command(std::string_view command, std::istream& in, std::string_view input_name, int status,
                          bool stats, const std::string& stats_text) {
  std::cout.flush();
  if (in.bad() || !std::cout) {
    std::cerr << "raykernel " << command << ": I/O error while "
              << (in.bad() ? "reading " + std::string(input_name) : std::string("writing output")) << "\n";
    return exit_usage;
  }
  if (stats) {
    std::istringstream lines(stats_text);
    for (std::string l; std::getline(lines, l);) std::cerr << "raykernel: stats: " << l << '\n';
  }
  return status;
}

std::string no_stages_text(Path path) {
  return std::string("path ") + (path == Path::exact ? "exact" : "naive") + ": no stages\n";
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
