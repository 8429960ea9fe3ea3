// What the mesh readers share: errors with positions, lines and tokens of text, numbers, and polygons.
#pragma once

#include <raykernel/io/mesh_file.hpp>
#include <raykernel/io/number.hpp>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace raykernel::io::detail {

// Meshes index vertices with 32 bits.
inline constexpr std::uint64_t max_vertices = std::numeric_limits<std::uint32_t>::max();

// The reader's file name, for its errors.
class ErrorSink {
 public:
  explicit ErrorSink(std::string_view file) : file_(file) {}
  [[noreturn]] void at_line(std::uint64_t line, const std::string& reason) const;
  [[noreturn]] void at_byte(std::uint64_t offset, const std::string& reason) const;
  [[noreturn]] void whole_file(const std::string& reason) const;

 private:
  std::string_view file_;
};

// A token as an error message quotes it: at most 40 characters, control and non-ASCII bytes escaped.
[[nodiscard]] std::string quote_token(std::string_view token);

constexpr bool is_blank(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// True when the text has nothing but blanks and line ends.
[[nodiscard]] bool only_whitespace(std::string_view text) noexcept;

// The lines of a text, without their "\n" or "\r\n". With `continuations`, a line ending in a backslash is
// joined with the next one (the backslash replaced by a blank), as OBJ allows; line_number() is then the
// number of the first of the joined lines.
class LineReader {
 public:
  LineReader(std::string_view text, bool continuations) : text_(text), continuations_(continuations) {}
  // The next line, or false at the end of the text.
  bool next(std::string_view& line);
  [[nodiscard]] std::uint64_t line_number() const noexcept { return line_number_; }
  // The offset of the first byte after the last line returned (after its line end).
  [[nodiscard]] std::size_t offset() const noexcept { return pos_; }

 private:
  std::string_view physical_line();
  std::string_view text_;
  bool continuations_;
  std::size_t pos_ = 0;
  std::uint64_t line_number_ = 0, next_line_number_ = 1;
  std::string joined_;
};

// The blank-separated tokens of a line; a token starting with '#' ends the line (a comment) when
// `comments` is set.
class Tokens {
 public:
  Tokens(std::string_view line, bool comments) : line_(line), comments_(comments) {}
  // The next token, or an empty view at the end.
  std::string_view next() noexcept {
    while (pos_ < line_.size() && is_blank(line_[pos_])) ++pos_;
    if (pos_ == line_.size() || (comments_ && line_[pos_] == '#')) {
      pos_ = line_.size();
      return {};
    }
    const std::size_t start = pos_;
    while (pos_ < line_.size() && !is_blank(line_[pos_])) ++pos_;
    return line_.substr(start, pos_ - start);
  }
  [[nodiscard]] bool at_end() noexcept {
    const std::size_t saved = pos_;
    const bool end = next().empty();
    pos_ = saved;
    return end;
  }

 private:
  std::string_view line_;
  bool comments_;
  std::size_t pos_ = 0;
};

// A coordinate at a line: the number, or the error naming it ("y of vertex 3") and saying why.
[[noreturn]] void bad_coordinate(const ErrorSink& errors, std::uint64_t line, std::string_view token, char axis,
                                 std::string_view element, std::uint64_t index, NumberError error);
[[nodiscard]] inline double coordinate_at_line(const ErrorSink& errors, std::uint64_t line, std::string_view token,
                                               char axis, std::string_view element, std::uint64_t index) {
  const NumberParse n = parse_double(token);
  if (!n.ok()) [[unlikely]]
    bad_coordinate(errors, line, token, axis, element, index, n.error);
  return n.value;
}

// A binary coordinate, widened: the error when it is NaN or infinite.
inline void check_finite_at_byte(const ErrorSink& errors, std::uint64_t offset, double value, std::string_view what) {
  if (value - value != 0) errors.at_byte(offset, std::string(what) + " is not finite");
}

// Appends the polygon `indices` (k ≥ 3, each < vertex count) fanned from its first vertex.
inline void add_polygon(Mesh& mesh, const std::uint32_t* indices, std::size_t k) {
  for (std::size_t i = 1; i + 1 < k; ++i) mesh.triangles.push_back({indices[0], indices[i], indices[i + 1]});
}

// "1 vertex", "3 vertices".
[[nodiscard]] std::string count_of(std::uint64_t n, std::string_view singular, std::string_view plural);

Mesh read_obj(std::string_view bytes, const ErrorSink& errors);
Mesh read_ply(std::string_view bytes, const ErrorSink& errors);
Mesh read_stl(std::string_view bytes, const ErrorSink& errors);
Mesh read_off(std::string_view bytes, const ErrorSink& errors);
// glTF 2.0, JSON or binary (GLB); external buffers are read from `folder` when it is given, else refused.
Mesh read_gltf(std::string_view bytes, const ErrorSink& errors, const std::filesystem::path* folder);

}  // namespace raykernel::io::detail
