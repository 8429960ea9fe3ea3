// The harnesses' own reading of the CLI's text formats (docs/contract.md §3–§4), written apart from cli/text_input.cpp
// so that the CLI harnesses check the CLI against an independent reading: lines as std::getline splits them,
// blank-separated tokens, numbers as C's strtod reads them.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::fuzz {

// The lines std::getline yields: split at '\n', the last piece only when it is not empty.
[[nodiscard]] std::vector<std::string_view> getline_lines(std::string_view text);

// The lines of an input file (queries, planes, rays) as docs/contract.md §3 reads them: getline_lines of the
// text after a UTF-8 byte-order mark (EF BB BF) at its very start, if any.
[[nodiscard]] std::vector<std::string_view> input_lines(std::string_view text);

// The contract's blanks: space, tab, CR, VT, FF.
[[nodiscard]] bool is_blank(char c);
[[nodiscard]] std::vector<std::string_view> tokens_of(std::string_view line);

// What a line of `count` numbers (≤ 12) is: skipped (blank, or '#' as the first non-blank character), or
// numbers (exactly `count` tokens, each read completely by strtod as a finite value that neither overflowed
// nor underflowed to zero — strtod's ERANGE with a zero result; a subnormal result is fine — `value` holds
// them), or neither (an invalid line).
struct ExpectedNumbers {
  bool skipped = false;
  bool numbers = false;
  std::array<double, 12> value{};
};
[[nodiscard]] ExpectedNumbers expected_numbers(std::string_view line, std::size_t count);

// `text` as a C string literal split at newlines ("...\n"\n"..."), for failure reports.
[[nodiscard]] std::string c_escaped(std::string_view text);

}  // namespace raykernel::fuzz
