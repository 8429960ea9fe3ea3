// What the stream commands share (classify, nearest, triangle, inside: a line of input in, a line of answer
// out): the --path option, the answer options, opening an input, and the end of a run (I/O errors, --stats).
#pragma once

#include "common/exit_status.hpp"
#include "common/io.hpp"

#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include <raykernel/triangle.hpp>

namespace raykernel::cli {

// The computation that answers (the --path option): the certified cascade, exact rationals alone, or the
// textbook formula in plain doubles (no guarantee).
enum class Method { certified, exact, naive };

// Reads `--path=X` or `--path X` at args[i] (advancing i past X in the second form) into `method`. On a
// missing or unknown value, prints "raykernel COMMAND: ..." on stderr and returns false.
[[nodiscard]] bool parse_method_option(std::string_view command, const std::vector<std::string>& args,
                                       std::size_t& i, Method& method);

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
  } else if (a == "--path" || a.starts_with("--path=")) {
    return parse_method_option(command, args, i, options.method) ? SharedOption::read : SharedOption::usage_error;
  } else {
    return SharedOption::not_shared;
  }
  return SharedOption::read;
}

// What an argument is: the first "--" (the end of the options: every later argument is an operand, even one
// starting with '-'), an option (starts with '-' and is not "-" alone), or an operand (a file; "-" is
// standard input). `options_ended` carries the state from one argument to the next.
enum class Argument { end_of_options, option, operand };
[[nodiscard]] Argument argument_kind(const std::string& arg, bool& options_ended);

// Keeps the one file operand a command takes in `path` and sets `given`; a second operand is a usage error:
// false after "raykernel COMMAND: more than one WHAT ('FIRST', 'SECOND')" on stderr.
[[nodiscard]] bool take_single_operand(std::string_view command, std::string_view what, const std::string& operand,
                                       std::string& path, bool& given);

// How messages name an input: "standard input" for "-" or "", else the path in quotes ('rays.txt').
[[nodiscard]] std::string input_name(const std::string& path);

// The --stats line of a method without stages: "path exact: no stages" or "path naive: no stages".
[[nodiscard]] std::string no_stages_text(Method method);

// Prints "raykernel COMMAND: cannot open WHAT 'PATH': REASON" and returns false when `input` did not open.
[[nodiscard]] bool check_opened(std::string_view command, std::string_view what, const std::string& path,
                                const Input& input);

// Ends a stream command: an output error (common/io.hpp) or an input error ("raykernel COMMAND: I/O error reading
// NAME: REASON") is exit status 2; otherwise prints the --stats text line by line as "raykernel: stats: ..."
// when asked, and returns `status`.
[[nodiscard]] int finish_stream_command(std::string_view command, const Input& input, std::string_view input_name,
                                        int status, bool stats, const std::string& stats_text);

// "filter N, compensated N, expansion N, exact N" for counts indexed by raykernel::Stage.
[[nodiscard]] std::string stage_counts_text(const std::uint64_t* counts);

// `--rule=X` or `--rule X` at args[i] (advancing i past X in the second form), X owned or closed; false after
// "raykernel COMMAND: ..." on stderr when X is missing or unknown.
[[nodiscard]] bool parse_rule_option(std::string_view command, const std::vector<std::string>& args, std::size_t& i,
                                     TriangleRule& rule);

// An invalid query line (docs/contract.md §3): "invalid REASON" on `out`, "raykernel: line N: REASON" on `err`.
void report_invalid_line(std::ostream& out, std::ostream& err, std::uint64_t line_number, const std::string& reason);

}  // namespace raykernel::cli
