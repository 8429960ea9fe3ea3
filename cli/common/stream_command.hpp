// What the stream commands share (classify, nearest, triangle, inside, spawn: a line of input in, a line of
// answer out): the values of --path and --rule, opening an input, the loop over the query lines and their
// invalid lines, and the end of a run (I/O errors, --stats).
#pragma once

#include "common/exit_status.hpp"
#include "common/io.hpp"
#include "common/options.hpp"
#include "common/text_input.hpp"

#include <cstdint>
#include <istream>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include <raykernel/triangle.hpp>

namespace raykernel::cli {

// The computation that answers (the --path option): the certified cascade, exact rationals alone, or the
// textbook formula in plain doubles (no guarantee).
enum class Method { certified, exact, naive };

// The values of --path, and of --rule (the triangle rule: docs/contract.md §6).
inline const Choices<Method> method_choices = {
    {"certified", Method::certified}, {"exact", Method::exact}, {"naive", Method::naive}};
inline const Choices<TriangleRule> rule_choices = {{"owned", TriangleRule::owned}, {"closed", TriangleRule::closed}};

// How messages name an input: "standard input" for "-" or "", else the path in quotes ('rays.txt').
[[nodiscard]] std::string input_name(const std::string& path);

// The --stats line of a method without stages: "path exact: no stages" or "path naive: no stages".
[[nodiscard]] std::string no_stages_text(Method method);

// Prints "raykernel COMMAND: cannot open WHAT 'PATH': REASON" and returns false when `input` did not open.
[[nodiscard]] bool check_opened(std::string_view command, std::string_view what, const std::string& path,
                                const Input& input);

// Ends a stream command: an output error (common/io.hpp) or an input error ("raykernel COMMAND: I/O error
// reading NAME: REASON") is exit status 2; otherwise prints the --stats text line by line as "raykernel:
// stats: ..." when asked, and returns `status`.
[[nodiscard]] int finish_stream_command(std::string_view command, const Input& input, std::string_view input_name,
                                        int status, bool stats, const std::string& stats_text);

// "filter N, compensated N, expansion N, exact N" for counts indexed by raykernel::Stage.
[[nodiscard]] std::string stage_counts_text(const std::uint64_t* counts);

// An invalid query line (docs/contract.md §3): "invalid REASON" on `out`, "raykernel: line N: REASON" on `err`.
void report_invalid_line(std::ostream& out, std::ostream& err, std::uint64_t line_number, const std::string& reason);

// The loop of every line-in, line-out command (docs/contract.md §3), written once: reads `in` line by line
// (LineReader: a byte-order mark skipped, lines of at most limits::max_line_bytes) until it ends or `out` fails;
// skips blank and # lines; gives every line of `expected` valid numbers to answer(line), which writes its answer
// line on `out`, or returns the reason the query is invalid; reports each invalid line (a bad or missing
// number, or answer's reason) with report_invalid_line. Counts the lines answered and the invalid ones;
// returns exit_ok, or exit_invalid_line when a line was invalid.
template <class Answer>  // std::optional<std::string>(const NumberLine&)
int answer_query_lines(std::istream& in, std::ostream& out, std::ostream& err, int expected,
                       std::uint64_t& lines_answered, std::uint64_t& invalid, Answer&& answer) {
  LineReader lines(in);
  std::string line;
  while (out && lines.next(line)) {
    const NumberLine parsed = parse_number_line(line, expected);
    if (parsed.status == LineStatus::skip) continue;
    ++lines_answered;
    std::optional<std::string> reason;
    if (parsed.status != LineStatus::numbers) reason = parsed.reason;
    else reason = answer(parsed);
    if (reason) {
      ++invalid;
      report_invalid_line(out, err, lines.line_number(), *reason);
    }
  }
  return invalid == 0 ? exit_ok : exit_invalid_line;
}

}  // namespace raykernel::cli
