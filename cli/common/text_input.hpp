// The text formats of the CLI (docs/contract.md §3–§4): lines of numbers in strtod syntax, and doubles printed so
// that strtod reads them back exactly.
#pragma once

#include "common/limits.hpp"

#include <array>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::cli {

inline constexpr int max_numbers_per_line = limits::max_numbers_per_line;

// The lines of a query, planes or rays file, as std::getline splits them, numbered from 1. A UTF-8
// byte-order mark (EF BB BF) at the very start of the input is dropped, as editors on some systems write it.
// A line longer than limits::max_line_bytes ends the input as a read error (the stream goes bad; on an
// Input's stream, Input::read_error() names the line and the limit): memory stays bounded on /dev/zero.
class LineReader {
 public:
  explicit LineReader(std::istream& in) noexcept : in_(in) {}
  // The next line into `line` (without its '\n'); false at the end of the input or when reading fails.
  [[nodiscard]] bool next(std::string& line);
  // The number of the line `next` returned last (1 for the first).
  [[nodiscard]] std::uint64_t line_number() const noexcept { return line_number_; }

 private:
  std::istream& in_;
  std::uint64_t line_number_ = 0;
};

enum class LineStatus { skip, numbers, invalid };

struct NumberLine {
  LineStatus status = LineStatus::skip;
  std::array<double, max_numbers_per_line> value{};  // the first `expected` entries, when status == numbers
  std::string reason;                                // when status == invalid
};

// Reads a line of exactly `expected` (≤ max_numbers_per_line) finite numbers separated by blanks (space, tab, CR, VT, FF).
// Blank lines and lines whose first non-blank character is '#' are `skip`. A number is anything C's strtod
// accepts in the "C" locale (decimal, scientific, hexadecimal with 0x) whose value, rounded to a double, is
// finite and is zero only when the number is zero: a value that overflows (1e400) or a nonzero value that
// rounds to zero (1e-400, -2e-324) is invalid; one that rounds to a subnormal (4e-324) is fine. Anything
// else is `invalid` with a reason naming the field and the token (quoted with printable bytes), or, for a
// wrong count, where the extra tokens start.
[[nodiscard]] NumberLine parse_number_line(std::string_view line, int expected);

// The same for a line of `expected` or `alternative` numbers (a ray alone, or with its interval: docs/contract.md
// §8); `count` says which. Field `infinity_field` (counted from 1; 0 for none) may also be +inf, in any spelling
// strtod reads as +inf ("inf", "+INF", "infinity"): a ray's t_max. A wrong count is "expected 6 or 8 numbers,
// found 7".
struct NumberLineOf {
  NumberLine line;
  int count = 0;
};
[[nodiscard]] NumberLineOf parse_number_line(std::string_view line, int expected, int alternative, int infinity_field);

// A ray line of docs/contract.md §8: `ox oy oz dx dy dz`, or with its interval `... t_min t_max` (t_max may be +inf
// in any strtod spelling); a bad bound's field is named ("field 8 (t_max): '1e400' overflows the double range").
[[nodiscard]] NumberLineOf parse_ray_line_with_interval(std::string_view line);

// The shortest decimal text that strtod reads back as exactly x ("inf", "-inf", "-0" included).
[[nodiscard]] std::string format_shortest(double x);
// The answer line of the nearest commands for a hit, without its newline: "hit K T", T as format_shortest
// prints it, or format_hex with `hex`.
[[nodiscard]] std::string hit_answer(std::size_t index, double t, bool hex);
// A hexadecimal float ("0x1.8p+1", "-0x0p+0", "inf"), exact by construction.
[[nodiscard]] std::string format_hex(double x);

// A file of primitives (planes, spheres), one per line of `count` numbers (§3's syntax: blank and # lines skipped,
// a byte-order mark dropped). The first invalid line — a bad number, or a primitive `validate` rejects — stops the
// reading: error_line and error name it, and items is empty.
template <class T>
struct PrimitiveFile {
  std::vector<T> items;
  std::uint64_t error_line = 0;  // 0 when every line was valid
  std::string error;
  [[nodiscard]] bool ok() const noexcept { return error_line == 0; }
};

// make(value) builds the primitive from the line's numbers; validate(primitive) names why it is invalid, or nothing.
template <class T, class Make, class Validate>
[[nodiscard]] PrimitiveFile<T> read_primitive_file(std::istream& in, int count, Make make, Validate validate) {
  PrimitiveFile<T> file;
  LineReader lines(in);
  std::string line;
  while (lines.next(line)) {
    const NumberLine parsed = parse_number_line(line, count);
    if (parsed.status == LineStatus::skip) continue;
    std::string reason = parsed.reason;
    if (parsed.status == LineStatus::numbers) {
      const T item = make(parsed.value);
      if (std::optional<std::string> invalid = validate(item)) reason = *invalid;
      else file.items.push_back(item);
    }
    if (!reason.empty()) {
      file.error_line = lines.line_number();
      file.error = reason;
      file.items.clear();
      return file;
    }
  }
  return file;
}

}  // namespace raykernel::cli
