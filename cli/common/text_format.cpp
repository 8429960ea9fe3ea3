#include "common/text_format.hpp"

#include <cstdarg>
#include <cstdio>

namespace raykernel::cli {

std::string with_thousands(std::uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string count_of(std::uint64_t n, std::string_view singular, std::string_view plural) {
  std::string out = with_thousands(n) + ' ';
  if (n == 1) out += singular;
  else if (!plural.empty()) out += plural;
  else (out += singular) += 's';
  return out;
}

std::string percent(std::uint64_t part, std::uint64_t whole, int decimals) {
  const double share = whole == 0 ? 0.0 : 100.0 * static_cast<double>(part) / static_cast<double>(whole);
  return formatted("%.*f%%", decimals, share);
}

std::string formatted(const char* format, ...) {
  std::va_list args;
  va_start(args, format);
  std::va_list again;
  va_copy(again, args);
  const int size = std::vsnprintf(nullptr, 0, format, args);
  va_end(args);
  std::string out(size > 0 ? static_cast<std::size_t>(size) : 0, '\0');
  if (size > 0) std::vsnprintf(out.data(), out.size() + 1, format, again);
  va_end(again);
  return out;
}

std::string rate(double per_second, std::string_view what) {
  const char* unit = "";
  double v = per_second;
  // The thresholds are where three significant digits would round up to 1000 of the smaller unit.
  if (v >= 999.5e3) {
    v /= 1e6;
    unit = "M ";
  } else if (v >= 999.5) {
    v /= 1e3;
    unit = "k ";
  }
  // Three significant digits after rounding: 9.996 shows as "10.0", not "10.00".
  std::string number;
  if (v == 0) number = "0";
  else if (v >= 99.95) number = formatted("%.0f", v);
  else if (v >= 9.995) number = formatted("%.1f", v);
  else if (v >= 0.9995) number = formatted("%.2f", v);
  else number = formatted("%.3g", v);
  return number + " " + unit + std::string(what);
}

std::string duration(double seconds) {
  if (seconds >= 100) return formatted("%.0f s", seconds);
  if (seconds >= 1) return formatted("%.3g s", seconds);
  if (seconds >= 0.1) return formatted("%.3f s", seconds);
  if (seconds >= 1e-3) return formatted("%.3g ms", seconds * 1e3);
  return formatted("%.3g \u00b5s", seconds * 1e6);
}

namespace {

// The length of the well-formed UTF-8 sequence starting at s[i] (RFC 3629: no overlong forms, no
// surrogates, nothing above U+10FFFF), or 0.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  std::size_t length;
  unsigned char low = 0x80, high = 0xbf;  // the range of the second byte
  if (b0 >= 0xc2 && b0 <= 0xdf) length = 2;
  else if (b0 >= 0xe0 && b0 <= 0xef) {
    length = 3;
    if (b0 == 0xe0) low = 0xa0;
    if (b0 == 0xed) high = 0x9f;
  } else if (b0 >= 0xf0 && b0 <= 0xf4) {
    length = 4;
    if (b0 == 0xf0) low = 0x90;
    if (b0 == 0xf4) high = 0x8f;
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if (byte(i + k) < 0x80 || byte(i + k) > 0xbf) return 0;
  return length;
}

// The code point of a well-formed UTF-8 sequence.
char32_t code_point(std::string_view sequence) {
  const auto b = [&](std::size_t k) { return static_cast<char32_t>(static_cast<unsigned char>(sequence[k])); };
  switch (sequence.size()) {
    case 2: return (b(0) & 0x1fu) << 6 | (b(1) & 0x3fu);
    case 3: return (b(0) & 0x0fu) << 12 | (b(1) & 0x3fu) << 6 | (b(2) & 0x3fu);
    default: return (b(0) & 0x07u) << 18 | (b(1) & 0x3fu) << 12 | (b(2) & 0x3fu) << 6 | (b(3) & 0x3fu);
  }
}

// Characters that print as nothing, as a blank that is not a space, or change how the rest of a line prints
// (Unicode 15): every Default_Ignorable_Code_Point (DerivedCoreProperties.txt: soft hyphen, combining
// grapheme joiner, Arabic letter mark, Hangul fillers, Khmer and Mongolian invisibles, zero-width and
// direction marks, direction embeddings and isolates, invisible operators, variation selectors, the byte-order
// mark, the tags and the reserved U+E0000 block); every other format character (Cf: Arabic number signs,
// interlinear annotations, Egyptian format controls, musical format controls); C1 controls; every space
// separator but U+0020 (Zs: no-break and fixed-width spaces), the line and paragraph separators (Zl, Zp) and
// the Braille blank; private-use characters and noncharacters, which print as whatever a font makes of them.
// Sorted, disjoint, inclusive.
constexpr struct {
  char32_t first, last;
} invisible_ranges[] = {
    {0x0080, 0x00a0},   {0x00ad, 0x00ad},   {0x034f, 0x034f},   {0x0600, 0x0605},   {0x061c, 0x061c},
    {0x06dd, 0x06dd},   {0x070f, 0x070f},   {0x0890, 0x0891},   {0x08e2, 0x08e2},   {0x115f, 0x1160},
    {0x1680, 0x1680},   {0x17b4, 0x17b5},   {0x180b, 0x180f},   {0x2000, 0x200f},   {0x2028, 0x202f},
    {0x205f, 0x206f},   {0x2800, 0x2800},   {0x3000, 0x3000},   {0x3164, 0x3164},   {0xe000, 0xf8ff},
    {0xfdd0, 0xfdef},   {0xfe00, 0xfe0f},   {0xfeff, 0xfeff},   {0xffa0, 0xffa0},   {0xfff0, 0xfffb},
    {0x110bd, 0x110bd}, {0x110cd, 0x110cd}, {0x13430, 0x1343f}, {0x1bca0, 0x1bca3}, {0x1d173, 0x1d17a},
    {0xe0000, 0xe0fff}, {0xf0000, 0x10ffff},
};

bool invisible(char32_t c) {
  if ((c & 0xfffe) == 0xfffe) return true;  // the noncharacters U+xFFFE and U+xFFFF of every plane
  for (const auto& r : invisible_ranges)
    if (c <= r.last) return c >= r.first;
  return false;
}

void append_escaped(std::string& out, unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02x", c);
  out += buf;
}

}  // namespace

std::string printable(std::string_view bytes) {
  std::string out;
  out.reserve(bytes.size());
  for (std::size_t i = 0; i < bytes.size();) {
    const auto c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    const std::size_t length = c >= 0x80 ? utf8_sequence_length(bytes, i) : 0;
    if (length == 0 || invisible(code_point(bytes.substr(i, length)))) {
      append_escaped(out, c);
      ++i;
      continue;
    }
    out.append(bytes.substr(i, length));
    i += length;
  }
  return out;
}

std::string quote(std::string_view text, std::size_t max_bytes) {
  std::size_t shown = text.size();
  if (shown > max_bytes) {
    shown = max_bytes;
    // Do not cut a UTF-8 sequence: back up over continuation bytes to the start of the last character.
    for (int k = 0; k < 3 && shown > 0 && (static_cast<unsigned char>(text[shown]) & 0xc0) == 0x80; ++k) --shown;
  }
  std::string out(1, '\'');
  out += printable(text.substr(0, shown));
  if (shown < text.size()) out += "...";
  out += '\'';
  return out;
}

}  // namespace raykernel::cli
