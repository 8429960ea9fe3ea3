#include "scenes/json_locator.hpp"

#include <raykernel/io/number.hpp>
#include "common/limits.hpp"
#include "common/text_format.hpp"

#include <set>
#include <vector>

namespace raykernel::cli {

using nlohmann::json;

void append_json_pointer_token(std::string& pointer, std::string_view key) {
  pointer += '/';
  for (char c : key) {
    if (c == '~') pointer += "~0";
    else if (c == '/') pointer += "~1";
    else pointer += c;
  }
}
void append_json_pointer_token(std::string& pointer, std::size_t index) {
  pointer += '/';
  pointer += std::to_string(index);
}

std::string json_pointer_child(const std::string& pointer, std::string_view key) {
  std::string out = pointer;
  append_json_pointer_token(out, key);
  return out;
}
std::string json_pointer_child(const std::string& pointer, std::size_t index) {
  std::string out = pointer;
  append_json_pointer_token(out, index);
  return out;
}

std::optional<std::variant<std::uint64_t, std::int64_t>> json_integer_value(std::string_view text) {
  // JSON's grammar: -? int (. digits)? ([eE] [+-]? digits)?
  std::size_t i = 0;
  const bool negative = i < text.size() && text[i] == '-';
  if (negative) ++i;
  std::string digits;  // the significand's digits, integer part then fraction
  long long scale = 0;   // value = digits · 10^scale
  auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
  for (; i < text.size() && is_digit(text[i]); ++i) digits += text[i];
  if (i < text.size() && text[i] == '.')
    for (++i; i < text.size() && is_digit(text[i]); ++i, --scale) digits += text[i];
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    const bool negative_exponent = i < text.size() && text[i] == '-';
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    long long exponent = 0;
    for (; i < text.size() && is_digit(text[i]); ++i)
      exponent = std::min(exponent * 10 + (text[i] - '0'), 1'000'000LL);  // saturates far beyond 20 digits
    scale += negative_exponent ? -exponent : exponent;
  }
  if (i != text.size() || digits.empty()) return std::nullopt;  // not a JSON number

  const std::size_t first = digits.find_first_not_of('0');
  if (first == std::string::npos) {  // zero
    if (negative) return std::nullopt;
    return std::uint64_t{0};
  }
  digits.erase(0, first);
  while (digits.back() == '0') {
    digits.pop_back();
    ++scale;
  }
  if (scale < 0) return std::nullopt;  // a nonzero last digit after the decimal point: not an integer
  if (static_cast<long long>(digits.size()) + scale > 20) return std::nullopt;  // beyond 2^64
  std::uint64_t v = 0;
  const auto times_ten_plus = [&v](std::uint64_t digit) {
    if (v > (UINT64_MAX - digit) / 10) return false;
    v = v * 10 + digit;
    return true;
  };
  for (char c : digits)
    if (!times_ten_plus(static_cast<std::uint64_t>(c - '0'))) return std::nullopt;
  for (long long k = 0; k < scale; ++k)
    if (!times_ten_plus(0)) return std::nullopt;
  if (!negative) return v;
  if (v > std::uint64_t{1} << 63) return std::nullopt;
  return v == std::uint64_t{1} << 63 ? INT64_MIN : -static_cast<std::int64_t>(v);
}

namespace {

// Forwards every event to nlohmann's DOM builder and keeps the pointer of the value being parsed.
class LocatingSax {
 public:
  explicit LocatingSax(json& root) : dom_(root, false) {}

  bool null() { return value(), dom_.null(); }
  bool boolean(bool v) { return value(), dom_.boolean(v); }
  bool number_integer(json::number_integer_t v) { return value(), dom_.number_integer(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(), dom_.number_unsigned(v); }
  bool number_float(json::number_float_t v, const json::string_t& s) {
    value();
    // JSON numbers are strtod numbers; the one number reader says whether a nonzero one rounded to zero.
    if (v == 0 && io::parse_double(s).error == io::NumberError::underflow)
      note_problem(quote(s) + " " + std::string(io::describe(io::NumberError::underflow)));
    if (const auto integer = json_integer_value(s)) {
      if (const auto* u = std::get_if<std::uint64_t>(&*integer)) return dom_.number_unsigned(*u);
      return dom_.number_integer(std::get<std::int64_t>(*integer));
    }
    return dom_.number_float(v, s);
  }
  bool string(json::string_t& v) { return value(), dom_.string(v); }
  bool binary(json::binary_t& v) { return value(), dom_.binary(v); }
  bool start_object(std::size_t n) {
    value();
    if (too_deep()) return false;
    frames_.push_back({false, -1, {}, {}});
    return dom_.start_object(n);
  }
  bool key(json::string_t& k) {
    Frame& frame = frames_.back();
    frame.key = k;
    if (!frame.keys.insert(k).second) note_problem("duplicate key: this member appears more than once in its object");
    return dom_.key(k);
  }
  bool end_object() {
    frames_.pop_back();
    return dom_.end_object();
  }
  bool start_array(std::size_t n) {
    value();
    if (too_deep()) return false;
    frames_.push_back({true, -1, {}, {}});
    return dom_.start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& last_token, const Exception& ex) {
    // `position` is just past the offending token: point at its first character.
    error_position_ = position >= last_token.size() ? position - last_token.size() : 0;
    error_id_ = ex.id;
    error_what_ = ex.what();
    error_pointer_ = pointer(Which::next);
    return dom_.parse_error(position, last_token, ex);
  }

  [[nodiscard]] bool failed() const noexcept { return error_id_ != 0 || too_deep_; }
  // Parsing stopped at an array or object nested deeper than limits::max_json_depth; error_pointer() is its.
  [[nodiscard]] bool nested_too_deep() const noexcept { return too_deep_; }
  [[nodiscard]] int error_id() const noexcept { return error_id_; }
  [[nodiscard]] std::size_t error_position() const noexcept { return error_position_; }
  [[nodiscard]] const std::string& error_what() const noexcept { return error_what_; }
  [[nodiscard]] const std::string& error_pointer() const noexcept { return error_pointer_; }
  // The first problem of a well-formed text, in document order: a key found twice in one object, or a
  // nonzero number that rounds to zero. Empty when none.
  [[nodiscard]] const std::string& problem() const noexcept { return problem_; }
  [[nodiscard]] const std::string& problem_pointer() const noexcept { return problem_pointer_; }

 private:
  struct Frame {
    bool array;
    long index;                  // the element being parsed (arrays)
    std::string key;             // the member being parsed (objects)
    std::set<std::string> keys;  // the keys seen so far (objects)
  };
  void value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  // An array or object about to start one level too deep: stop (the DOM, nlohmann's recursion and the frames
  // would otherwise grow with the nesting: 10^7 levels took 2.2 GB).
  bool too_deep() {
    if (frames_.size() < limits::max_json_depth) return false;
    too_deep_ = true;
    error_pointer_ = pointer(Which::current);
    return true;
  }
  // Keeps the first problem, at the value being parsed; parsing goes on, so that a syntax error later in
  // the text is still the one reported.
  void note_problem(std::string message) {
    if (!problem_.empty()) return;
    problem_ = std::move(message);
    problem_pointer_ = pointer(Which::current);
  }
  // The pointer of the value just started (current: a number being reported, a key just read) or of the
  // value the parser is about to read (next: where a syntax error is): in an array, the last element
  // started or the one after it; in an object, the member of the last key either way.
  enum class Which { current, next };
  // Built in place: linear in its length (a copy per level made 10^6 levels take 48 s).
  [[nodiscard]] std::string pointer(Which which) const {
    std::string p;
    for (std::size_t f = 0; f < frames_.size(); ++f) {
      const Frame& frame = frames_[f];
      const bool after = which == Which::next && f + 1 == frames_.size();
      if (frame.array) append_json_pointer_token(p, static_cast<std::size_t>(frame.index + (after ? 1 : 0)));
      else append_json_pointer_token(p, frame.key);
    }
    return p;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::vector<Frame> frames_;
  int error_id_ = 0;
  bool too_deep_ = false;
  std::size_t error_position_ = 0;
  std::string error_what_, error_pointer_;
  std::string problem_, problem_pointer_;
};

// "line L, column C" of a byte offset (1-based, as nlohmann counts).
std::string line_and_column(std::string_view text, std::size_t position) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < position && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string without_prefix(const std::string& what) {
  const std::size_t end = what.find("] ");
  return end == std::string::npos ? what : what.substr(end + 2);
}

}  // namespace

LocatedJson parse_located_json(std::string_view text) {
  LocatedJson r;
  LocatingSax sax(r.document);
  const bool parsed = json::sax_parse(text.begin(), text.end(), &sax, nlohmann::detail::input_format_t::json, true);
  if (!parsed || sax.failed()) {
    r.document = nullptr;
    if (sax.nested_too_deep()) {
      r.error_pointer = sax.error_pointer();
      r.error = "arrays and objects nested deeper than " + std::to_string(limits::max_json_depth) + " levels";
    } else if (sax.error_id() == 406) {  // a number outside the double range: its value is known
      r.error_pointer = sax.error_pointer();
      r.error = "number outside the double range (not finite), at " + line_and_column(text, sax.error_position());
    } else {
      r.error = "invalid JSON: " + without_prefix(sax.error_what());
    }
    return r;
  }
  if (!sax.problem().empty()) {
    r.document = nullptr;
    r.error_pointer = sax.problem_pointer();
    r.error = sax.problem();
  }
  return r;
}

}  // namespace raykernel::cli
