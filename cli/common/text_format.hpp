// Text the CLI shows people, written one way everywhere: counts with thousands separators and plurals,
// percentages, rates, and bytes from the input made safe to print (every message quotes user text through
// printable or quoted, so a control byte or broken UTF-8 never reaches a terminal).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace raykernel::cli {

// 1234567 → "1,234,567".
[[nodiscard]] std::string with_thousands(std::uint64_t n);

// "1 plane", "2,073,600 rays": the count with thousands separators and the noun, plural unless n is 1
// (`plural` defaults to the singular with an "s").
[[nodiscard]] std::string count_of(std::uint64_t n, std::string_view singular, std::string_view plural = {});

// 100·part/whole with `decimals` decimals and a percent sign ("26.52%"; "0.00%" when whole is 0).
[[nodiscard]] std::string percent(std::uint64_t part, std::uint64_t whole, int decimals = 2);

// A rate with three significant digits in the unit that keeps it readable and never shows 0.00:
// "4.31 M rays/s", "812 k rays/s", "35.2 rays/s" (what = "rays/s"). Above 999.5 the value moves to k, above
// 999,500 to M; a zero rate is "0 rays/s".
[[nodiscard]] std::string rate(double per_second, std::string_view what);

// A duration with three significant digits: "0.481 s", "2.35 s", "12.3 ms", "85.1 µs".
[[nodiscard]] std::string duration(double seconds);

// printf into a std::string.
[[nodiscard]] std::string formatted(const char* format, ...) __attribute__((format(printf, 1, 2)));

// `bytes` with every byte that is not printable text escaped as \xNN: C0 controls, DEL, bytes that are not
// part of well-formed UTF-8, and the bytes of characters that print as nothing, as a blank other than a
// space, or reorder text (C1 controls, every default-ignorable and format character — zero-width and
// direction marks, soft hyphen, tags, variation selectors, the byte-order mark U+FEFF —, no-break and other
// spaces, line separators, private-use characters, noncharacters). Printable ASCII and other well-formed
// UTF-8 pass unchanged; a backslash is not escaped.
[[nodiscard]] std::string printable(std::string_view bytes);

// 'TEXT' for messages: printable(text) between single quotes, cut after `max_bytes` bytes (at a character
// boundary) with "..." when longer.
[[nodiscard]] std::string quote(std::string_view text, std::size_t max_bytes = 40);

}  // namespace raykernel::cli
