// Command-line pieces shared by the stream commands (classify, nearest): the --path option, opening an
// input file or standard input, and the end of a run (I/O errors, --stats).
#pragma once

#include "commands.hpp"

#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::cli {

// Reads `--path=X` or `--path X` at args[i] (advancing i past X in the second form) into `path`. On a
// missing or unknown value, prints "raykernel COMMAND: ..." on stderr and returns false.
[[nodiscard]] bool parse_path_option(std::string_view command, const std::vector<std::string>& args, std::size_t& i,
                                     Path& path);

// The answer options classify and nearest share: --exact-t, --hex, --stats and --path X, read from args[i]
// (advancing i past a separate --path value) into `options`, whose members of those names both option
// structs have.
enum class SharedOption { read, not_shared, usage_error };
template <class Options>
[[nodiscard]] SharedOption parse_shared_option(std::string_view command, const std::vector<std::string>& args,
                                               std::size_t& i, Options& options) {
  const std::string& a = args[i];
  if (a == "--exact-t") {
    options.exact_t = true;
  } else if (a == "--hex") {
    options.hex = true;
  } else if (a == "--stats") {
    options.stats = true;
  } else if (a.rfind("--path", 0) == 0) {
    return parse_path_option(command, args, i, options.path) ? SharedOption::read : SharedOption::usage_error;
  } else {
    return SharedOption::not_shared;
  }
  return SharedOption::read;
}

// The --stats line of a path without stages: "path exact: no stages" or "path naive: no stages".
[[nodiscard]] std::string no_stages_text(Path path);

// The stream to read: standard input for "" or "-", else the file (opened into `storage`). Prints
// "raykernel COMMAND: cannot open WHAT 'PATH'" and returns nullptr when the file cannot be opened.
[[nodiscard]] std::istream* open_input(std::string_view command, std::string_view what, const std::string& path,
                                       std::ifstream& storage);

// Ends a stream command: flushes stdout; an input or output error (a directory given as a file, a closed
// pipe) is a usage/I-O error (exit 2); otherwise prints the --stats text line by line as
// "raykernel: stats: ..." when asked, and returns `status`.
[[nodiscard]] int finish_stream_command(std::string_view command, std::istream& in, std::string_view input_name,
                                        int status, bool stats, const std::string& stats_text);

// "filter N, compensated N, expansion N, exact N" for counts indexed by raykernel::Stage.
[[nodiscard]] std::string stage_counts_text(const std::uint64_t* counts);

// An invalid query line (docs/contract.md §3): "invalid REASON" on `out`, "raykernel: line N: REASON" on `err`.
void report_invalid_line(std::ostream& out, std::ostream& err, std::uint64_t line_number, const std::string& reason);

}  // namespace raykernel::cli
