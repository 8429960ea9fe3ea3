// The OBJ reader (Wavefront OBJ, geometry statements): `v x y z [w | r g b]` adds a vertex; `f a b c ...`
// (each vertex reference `i`, `i/t`, `i//n` or `i/t/n`; 1-based, or negative: relative to the vertices
// read so far) adds a polygon, fanned. Every other statement of the OBJ specification (vt, vn, vp, l, p, o,
// g, s, usemtl, mtllib, free-form geometry, ...) is read and ignored; an unknown statement is an error.
// '#' starts a comment, a backslash at the end of a line continues it, CRLF line ends are fine. Positive
// indices may refer to vertices defined later in the file (they are checked at its end).
#include "reader_support.hpp"

#include <array>
#include <charconv>

namespace raykernel::io::detail {
namespace {

// Statements the OBJ specification (and common practice) defines that carry no triangle geometry.
constexpr std::array<std::string_view, 38> ignored_statements = {
    "vt", "vn", "vp", "l", "p", "o", "g", "s", "mg", "usemtl", "mtllib", "maplib", "usemap", "lod",
    "shadow_obj", "trace_obj", "bevel", "c_interp", "d_interp", "cstype", "deg", "bmat", "step", "curv",
    "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "con", "ctech", "stech", "call", "csh", "res"};

bool is_ignored_statement(std::string_view keyword) {
  for (std::string_view s : ignored_statements)
    if (s == keyword) return true;
  return false;
}

// An integer reference (vertex, texture or normal index) of a face: nonzero, fits in 64 bits.
bool parse_reference(std::string_view text, std::int64_t& value) {
  if (text.empty()) return false;
  const char* first = text.data();
  if (*first == '+') ++first;
  const auto r = std::from_chars(first, text.data() + text.size(), value);
  return r.ec == std::errc{} && r.ptr == text.data() + text.size() && (first == text.data() || value >= 0);
}

}  // namespace

Mesh read_obj(std::string_view bytes, const ErrorSink& errors) {
  Mesh mesh;
  LineReader lines(bytes, /*continuations=*/true);
  std::string_view line;
  std::vector<std::uint32_t> polygon;
  std::uint64_t statements = 0;
  std::int64_t largest_index = 0;      // the largest positive vertex index of any face
  std::uint64_t largest_index_line = 0;  // and the first line it appears on
  // Forward references are resolved at the end; until then positive indices are stored as given − 1.
  while (lines.next(line)) {
    Tokens tokens(line, /*comments=*/true);
    const std::string_view keyword = tokens.next();
    if (keyword.empty()) continue;
    ++statements;
    const std::uint64_t n = lines.line_number();
    if (keyword == "v") {
      if (mesh.vertices.size() >= max_vertices) errors.at_line(n, "too many vertices (meshes index with 32 bits)");
      const std::uint64_t vertex = mesh.vertices.size() + 1;  // OBJ numbers vertices from 1
      Vec3 v{};
      v.x = coordinate_at_line(errors, n, tokens.next(), 'x', "vertex", vertex);
      v.y = coordinate_at_line(errors, n, tokens.next(), 'y', "vertex", vertex);
      v.z = coordinate_at_line(errors, n, tokens.next(), 'z', "vertex", vertex);
      // w (rational curves) or a colour r g b: numbers whose values do not matter here.
      int extra = 0;
      for (std::string_view t = tokens.next(); !t.empty(); t = tokens.next(), ++extra) {
        if (extra == 4) errors.at_line(n, "a vertex has at most 7 values (x y z and w or a colour)");
        if (parse_double(t).error == NumberError::not_a_number)
          errors.at_line(n, "value " + std::to_string(extra + 4) + " of vertex " + std::to_string(vertex) + ": " + quote_token(t) + " is not a number");
      }
      mesh.vertices.push_back(v);
    } else if (keyword == "f") {
      polygon.clear();
      for (std::string_view ref = tokens.next(); !ref.empty(); ref = tokens.next()) {
        const std::size_t slash = ref.find('/');
        const std::string_view vertex_part = ref.substr(0, slash);
        std::int64_t index = 0;
        if (!parse_reference(vertex_part, index))
          errors.at_line(n, "face vertex " + quote_token(ref) + " is not a vertex index");
        if (slash != std::string_view::npos) {  // i/t, i//n, i/t/n: t and n are ignored but must be integers
          const std::string_view rest = ref.substr(slash + 1);
          const std::size_t slash2 = rest.find('/');
          const std::string_view texture = rest.substr(0, slash2);
          const std::string_view normal = slash2 == std::string_view::npos ? std::string_view{} : rest.substr(slash2 + 1);
          std::int64_t ignored = 0;
          const bool texture_ok = texture.empty() ? slash2 != std::string_view::npos : parse_reference(texture, ignored);
          const bool normal_ok = slash2 == std::string_view::npos || parse_reference(normal, ignored);
          if (!texture_ok || !normal_ok) errors.at_line(n, "face vertex " + quote_token(ref) + " is not of the form i, i/t, i//n or i/t/n");
        }
        const auto count = static_cast<std::int64_t>(mesh.vertices.size());
        if (index == 0) errors.at_line(n, "vertex index 0 is out of range (OBJ counts vertices from 1)");
        if (index < 0) {
          // −index overflows for INT64_MIN: compare without negating.
          if (index < -count)
            errors.at_line(n, "relative vertex index " + std::to_string(index) + " is out of range (" +
                                  count_of(static_cast<std::uint64_t>(count), "vertex", "vertices") + " so far)");
          polygon.push_back(static_cast<std::uint32_t>(count + index));
        } else {
          if (index > static_cast<std::int64_t>(max_vertices))
            errors.at_line(n, "vertex index " + std::to_string(index) + " is out of range");
          if (index > largest_index) {
            largest_index = index;
            largest_index_line = n;
          }
          polygon.push_back(static_cast<std::uint32_t>(index - 1));
        }
      }
      if (polygon.size() < 3)
        errors.at_line(n, "a face needs at least 3 vertices, this one has " + std::to_string(polygon.size()));
      add_polygon(mesh, polygon.data(), polygon.size());
    } else if (!is_ignored_statement(keyword)) {
      errors.at_line(n, "unknown statement " + quote_token(keyword));
    }
  }
  // A file of comments only is an OBJ file describing nothing (an empty mesh, as write_mesh writes one);
  // a file with nothing at all is an error.
  if (statements == 0 && only_whitespace(bytes)) errors.whole_file("empty file");
  if (largest_index > static_cast<std::int64_t>(mesh.vertices.size()))
    errors.at_line(largest_index_line, "vertex index " + std::to_string(largest_index) + " is out of range (the file has " +
                                           count_of(mesh.vertices.size(), "vertex", "vertices") + ")");
  return mesh;
}

}  // namespace raykernel::io::detail
