// JSON with the location of every problem, for scene files: the JSON Pointer (RFC 6901) of the offending
// value, and for syntax errors the line and column. nlohmann-json's parser runs through its SAX interface
// so that
//   - a number outside the double range (which nlohmann reports without a location) gets its pointer;
//   - a key that appears twice in one object (which nlohmann's DOM silently resolves to one) is an error at
//     its pointer;
//   - a number written with a fraction or an exponent whose value is an integer that fits in 64 bits ("1e3",
//     "2.50e1", "7.0") becomes that integer, so that integer fields accept it. (Its double value is the same:
//     the integer rounded to a double is the text rounded to a double.) "-0.0" stays a double.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace raykernel::cli {

// The pointer of a member or an element below `pointer` ("~" and "/" in keys escaped as "~0" and "~1"), as a
// new string or appended in place.
void append_json_pointer_token(std::string& pointer, std::string_view key);
void append_json_pointer_token(std::string& pointer, std::size_t index);
[[nodiscard]] std::string json_pointer_child(const std::string& pointer, std::string_view key);
[[nodiscard]] std::string json_pointer_child(const std::string& pointer, std::size_t index);

// The document, or where and why the text is not one. Arrays and objects nested deeper than
// limits::max_json_depth are an error at the pointer of the first one too deep.
struct LocatedJson {
  nlohmann::json document;    // when error is empty
  std::string error_pointer;  // "" for the document itself and for syntax errors
  std::string error;          // "" when the text is a JSON document without duplicate keys
};
[[nodiscard]] LocatedJson parse_located_json(std::string_view text);

// The integer a JSON number's text denotes, when it is an integer that fits: a std::uint64_t for a value
// ≥ 0 (+0 only: "-0" is not one), a std::int64_t for a negative value ≥ −2^63. Exact, from the digits: "1e3"
// is 1000, "1.5e1" is 15, "1.0000000000000000001" is not an integer.
[[nodiscard]] std::optional<std::variant<std::uint64_t, std::int64_t>> json_integer_value(std::string_view number);

}  // namespace raykernel::cli
