// fuzz_cli: arbitrary text through `raykernel classify` (cli::classify_stream, the code the binary runs) and
// its line parser cli::parse_number_line (docs/contract.md §3).
//
// The input is the whole text of an input file. It is classified three times — default options; --path=exact
// --exact-t --hex --stats; --path=naive --exact-t — and for each run the harness checks, against its own
// reading of the text:
//   - lines are split as std::getline splits them, after a UTF-8 byte-order mark at the start, and numbered
//     from 1; blank lines and lines whose first non-blank character is '#' produce no output; every other line produces exactly one output line, in
//     order, and nothing else is written to stdout;
//   - a line is a query when it has exactly 12 blank-separated tokens, each read completely by strtod as a
//     finite value that neither overflowed nor underflowed to zero (strtod's ERANGE; the values must be the
//     ones strtod reads), and the direction and
//     normal are nonzero; any other line is answered `invalid REASON` on stdout and reported as
//     `raykernel: line N: REASON` on stderr, with the same REASON and the right N, and nothing else goes to
//     stderr;
//   - a query is answered `RELATION [T [P/Q]]` with the relation and t of intersect (certified),
//     intersect_exact (exact), T read back by strtod to exactly t's bits, P/Q the exact t; the naive path
//     only has to answer every line;
//   - the exit status is 0 when every line was valid, 1 otherwise; the counts add up.
#include "fuzz_support.hpp"
#include "fuzz_text.hpp"

#include "commands/plane_classify.hpp"
#include "common/text_input.hpp"

#include <raykernel/raykernel.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace {

using raykernel::fuzz::check;
namespace cli = raykernel::cli;

std::string_view current_text;

std::string describe_current() {
  return "input text (" + std::to_string(current_text.size()) + " bytes, C-escaped):\n" +
         raykernel::fuzz::c_escaped(current_text);
}

using raykernel::fuzz::getline_lines;
using raykernel::fuzz::tokens_of;

// What docs/contract.md §3 says a line is, by the harness's own reading.
struct ExpectedLine {
  bool skipped = false;
  bool valid = false;
  std::array<double, 12> value{};
};

ExpectedLine expected_line(std::string_view line) {
  const raykernel::fuzz::ExpectedNumbers numbers = raykernel::fuzz::expected_numbers(line, 12);
  ExpectedLine e{numbers.skipped, false, numbers.value};
  if (!numbers.numbers) return e;
  auto zero = [](double a, double b, double c) { return a == 0 && b == 0 && c == 0; };
  e.valid = !zero(e.value[3], e.value[4], e.value[5]) && !zero(e.value[9], e.value[10], e.value[11]);
  return e;
}

struct Run {
  cli::ClassifyOptions options;
  const char* name;
};

void check_run(std::string_view text, const std::vector<std::string_view>& lines, const Run& run) {
  std::istringstream in{std::string(text)};
  std::ostringstream out, err;
  cli::ClassifyCounts counts;
  const int status = cli::classify_stream(in, out, err, run.options, counts);
  (void)cli::describe(counts, run.options.method);
  // Message prefixes, built only when a check fails.
  auto run_label = [&] { return std::string("[") + run.name + "] "; };
  std::size_t i = 0;  // the current line, from 0
  auto at = [&](std::string_view what) {
    return run_label() + "line " + std::to_string(i + 1) + ": " + std::string(what);
  };

  // str(), not view(): ostringstream::view() needs libc++ 17 (ClusterFuzzLite's is newer; clang-14's is not).
  const std::string out_text = out.str(), err_text = err.str();
  const std::vector<std::string_view> out_lines = getline_lines(out_text);
  const std::vector<std::string_view> err_lines = getline_lines(err_text);
  check(out_text.empty() || out_text.back() == '\n', [&] { return run_label() + "stdout ends with a newline"; });
  check(err_text.empty() || err_text.back() == '\n', [&] { return run_label() + "stderr ends with a newline"; });

  std::size_t next_out = 0, next_err = 0, answered = 0, invalid = 0, valid = 0, with_t = 0;
  for (i = 0; i < lines.size(); ++i) {
    const ExpectedLine expected = expected_line(lines[i]);
    const cli::NumberLine parsed = cli::parse_number_line(lines[i], 12);
    check((parsed.status == cli::LineStatus::skip) == expected.skipped,
          [&] { return at("skipped exactly when blank or starting with '#'"); });
    if (expected.skipped) continue;
    ++answered;
    check(next_out < out_lines.size(), [&] { return at("has an output line"); });
    const std::string_view answer = out_lines[next_out++];

    if (parsed.status == cli::LineStatus::numbers) {
      for (std::size_t k = 0; k < 12; ++k) {
        check(std::bit_cast<std::uint64_t>(parsed.value[k]) == std::bit_cast<std::uint64_t>(expected.value[k]),
              [&] { return at("field " + std::to_string(k + 1) + " is the double strtod reads"); });
      }
    } else {
      check(!parsed.reason.empty(), [&] { return at("parse_number_line gives a reason"); });
    }

    if (!expected.valid) {
      ++invalid;
      check(answer.starts_with("invalid ") && answer.size() > 8,
            [&] { return at("answered 'invalid REASON', got '" + std::string(answer) + "'"); });
      check(next_err < err_lines.size(), [&] { return at("reported on stderr"); });
      const std::string_view got = err_lines[next_err++];
      const std::string_view reason = answer.substr(8);
      const std::string_view prefix = "raykernel: line ";
      const std::string number = std::to_string(i + 1);
      check(got.size() == prefix.size() + number.size() + 2 + reason.size() && got.starts_with(prefix) &&
                got.substr(prefix.size(), number.size()) == number &&
                got.substr(prefix.size() + number.size(), 2) == ": " && got.ends_with(reason),
            [&] {
              return at("stderr says 'raykernel: line " + number + ": " + std::string(reason) + "', got '" +
                        std::string(got) + "'");
            });
      continue;
    }
    ++valid;
    check(parsed.status == cli::LineStatus::numbers, [&] { return at("a valid line parses as numbers"); });
    const double* v = expected.value.data();
    const raykernel::Ray ray{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    const raykernel::Plane plane{{v[6], v[7], v[8]}, {v[9], v[10], v[11]}};
    const std::vector<std::string_view> words = tokens_of(answer);
    check(!words.empty(), [&] { return at("the answer is not empty"); });
    if (run.options.method == cli::Method::naive) continue;  // no guarantee beyond answering

    const raykernel::Intersection want = run.options.method == cli::Method::exact ? raykernel::intersect_exact(ray, plane)
                                                                              : raykernel::intersect(ray, plane);
    const bool has_t = want.relation == raykernel::Relation::hit || want.relation == raykernel::Relation::behind;
    const std::size_t want_words = has_t ? (run.options.exact_t ? 3 : 2) : 1;
    check(words.size() == want_words && words[0] == raykernel::to_string(want.relation), [&] {
      return at("answers '" + std::string(raykernel::to_string(want.relation)) + "' in " + std::to_string(want_words) +
                " words, got '" + std::string(answer) + "'");
    });
    if (!has_t) continue;
    ++with_t;
    const std::string t_text(words[1]);
    char* end = nullptr;
    const double t = std::strtod(t_text.c_str(), &end);
    check(end == t_text.c_str() + t_text.size(), [&] { return at("T '" + t_text + "' is one strtod number"); });
    check(std::bit_cast<std::uint64_t>(t) == std::bit_cast<std::uint64_t>(want.t),
          [&] { return at("T '" + t_text + "' reads back as t = " + raykernel::fuzz::hex(want.t)); });
    if (run.options.hex) {
      check(t_text.find("0x") != std::string::npos || std::isinf(t), [&] { return at("--hex prints a hex float"); });
    }
    if (run.options.exact_t) {
      const raykernel::ExactIntersection exact = raykernel::intersect_exact_rational(ray, plane);
      check(exact.t && words[2] == exact.t->str(), [&] { return at("P/Q is the exact t"); });
    }
  }
  check(next_out == out_lines.size(), [&] { return run_label() + "no extra output lines"; });
  check(next_err == err_lines.size(), [&] { return run_label() + "no extra error lines"; });
  check(status == (invalid == 0 ? cli::exit_ok : cli::exit_invalid_line),
        [&] { return run_label() + "exit status 0 when every line is valid, else 1"; });
  check(counts.lines_answered == answered && counts.invalid == invalid,
        [&] { return run_label() + "counts of answered and invalid lines"; });
  std::uint64_t relations = 0, relation_stages = 0, t_stages = 0;
  for (int k = 0; k < 4; ++k) {
    relations += counts.relation[k];
    relation_stages += counts.relation_stage[k];
    t_stages += counts.t_stage[k];
  }
  check(relations == valid, [&] { return run_label() + "relation counts add up"; });
  if (run.options.method == cli::Method::certified) {
    check(relation_stages == valid, [&] { return run_label() + "relation stage counts add up"; });
    check(t_stages == with_t, [&] { return run_label() + "t stage counts add up"; });
  }
}

std::uint64_t executions = 0, lines_seen = 0, lines_valid = 0;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool initialized = [] {
    raykernel::fuzz::set_harness_name("cli");
    raykernel::fuzz::set_input_describer(describe_current);
    raykernel::fuzz::print_at_exit([] {
      std::fprintf(stderr, "==== raykernel fuzz stats: cli: %llu executions, %llu lines, %llu valid queries\n",
                   static_cast<unsigned long long>(executions), static_cast<unsigned long long>(lines_seen),
                   static_cast<unsigned long long>(lines_valid));
    });
    return true;
  }();
  (void)initialized;
  current_text = std::string_view(reinterpret_cast<const char*>(data), size);
  const std::vector<std::string_view> lines = raykernel::fuzz::input_lines(current_text);

  static const Run runs[] = {
      {{cli::Method::certified, false, false, false}, "default"},
      {{cli::Method::exact, true, true, true}, "--path=exact --exact-t --hex --stats"},
      {{cli::Method::naive, true, false, false}, "--path=naive --exact-t"},
  };
  for (const Run& run : runs) check_run(current_text, lines, run);

  ++executions;
  lines_seen += lines.size();
  for (std::string_view line : lines) lines_valid += expected_line(line).valid ? 1 : 0;
  return 0;
}
