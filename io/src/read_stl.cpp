// The STL reader. Binary: an 80-byte header, a little-endian uint32 facet count n, then n records of 50
// bytes (normal, three vertices as little-endian floats, a 16-bit attribute); recognized by its size, which
// must be exactly 84 + 50·n — even when the header starts with "solid", as many exporters write it. ASCII:
// `solid NAME` ... `endsolid NAME`, each `facet normal nx ny nz / outer loop / vertex x y z (three or more)
// / endloop / endfacet`; several solids may follow each other. Each facet adds its own vertices (nothing is
// welded) and its triangles (fanned, if a loop has more than three vertices). Normals and attributes are
// ignored (the normal's values must still be numbers in ASCII).
#include "reader_support.hpp"

#include <bit>
#include <cstring>

namespace raykernel::io::detail {
namespace {

std::uint32_t little_u32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + static_cast<std::size_t>(i)]);
  return v;
}

Mesh read_binary_stl(std::string_view bytes, std::uint32_t n, const ErrorSink& errors) {
  Mesh mesh;
  mesh.vertices.resize(3 * static_cast<std::size_t>(n));
  mesh.triangles.resize(n);
  static const char* const axis_name[3] = {"x", "y", "z"};
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::size_t record = 84 + 50 * static_cast<std::size_t>(k);
    for (std::uint32_t j = 0; j < 3; ++j) {
      double c[3];
      for (std::size_t axis = 0; axis < 3; ++axis) {
        const std::size_t at = record + 12 + 12 * j + 4 * axis;
        c[axis] = static_cast<double>(std::bit_cast<float>(little_u32(bytes, at)));
        if (c[axis] - c[axis] != 0)
          errors.at_byte(at, std::string(axis_name[axis]) + " of vertex " + std::to_string(j) + " of facet " +
                                 std::to_string(k) + " is not finite");
      }
      mesh.vertices[3 * static_cast<std::size_t>(k) + j] = {c[0], c[1], c[2]};
    }
    const auto first = static_cast<std::uint32_t>(3 * k);
    mesh.triangles[k] = {first, first + 1, first + 2};
  }
  return mesh;
}

// The tokens of an ASCII STL file, across lines, with their line numbers.
class TokenStream {
 public:
  explicit TokenStream(std::string_view text) : lines_(text, false), tokens_("", false) {}
  std::string_view next() {
    while (true) {
      const std::string_view t = tokens_.next();
      if (!t.empty()) {
        token_line_ = lines_.line_number();
        return t;
      }
      std::string_view line;
      if (!lines_.next(line)) {
        token_line_ = lines_.line_number();
        return {};
      }
      tokens_ = Tokens(line, false);
    }
  }
  // Skips the rest of the current line (a solid's name).
  void skip_line() { tokens_ = Tokens("", false); }
  [[nodiscard]] std::uint64_t line() const { return token_line_; }

 private:
  LineReader lines_;
  Tokens tokens_;
  std::uint64_t token_line_ = 1;
};

Mesh read_ascii_stl(std::string_view bytes, const ErrorSink& errors) {
  Mesh mesh;
  TokenStream in(bytes);
  auto expect = [&](std::string_view word, std::string_view after) {
    const std::string_view t = in.next();
    if (t != word)
      errors.at_line(in.line(), "expected '" + std::string(word) + "' " + std::string(after) + ", found " +
                                    (t.empty() ? std::string("the end of the file") : quote_token(t)));
  };
  std::string_view t = in.next();
  if (t.empty()) errors.whole_file("empty file");
  std::uint64_t facet = 0;
  std::vector<std::uint32_t> polygon;
  while (!t.empty()) {
    if (t != "solid") errors.at_line(in.line(), "expected 'solid', found " + quote_token(t) + " (not an STL file)");
    in.skip_line();
    while (true) {
      t = in.next();
      if (t == "endsolid") {
        in.skip_line();
        break;
      }
      if (t != "facet")
        errors.at_line(in.line(), "expected 'facet' or 'endsolid', found " +
                                      (t.empty() ? std::string("the end of the file") : quote_token(t)));
      expect("normal", "after 'facet'");
      for (char axis : {'x', 'y', 'z'}) {
        const std::string_view v = in.next();
        if (parse_double(v).error == NumberError::not_a_number)
          errors.at_line(in.line(), std::string("normal ") + axis + " of facet " + std::to_string(facet) + ": " +
                                        (v.empty() ? std::string("missing") : quote_token(v) + " is not a number"));
      }
      expect("outer", "after the facet's normal");
      expect("loop", "after 'outer'");
      polygon.clear();
      while (true) {
        t = in.next();
        if (t == "endloop") break;
        if (t != "vertex")
          errors.at_line(in.line(), "expected 'vertex' or 'endloop', found " +
                                        (t.empty() ? std::string("the end of the file") : quote_token(t)));
        if (mesh.vertices.size() >= max_vertices) errors.at_line(in.line(), "too many vertices (meshes index with 32 bits)");
        Vec3 v{};
        for (int axis = 0; axis < 3; ++axis) {
          const std::string_view c = in.next();
          (&v.x)[axis] = coordinate_at_line(errors, in.line(), c, static_cast<char>('x' + axis), "a vertex of facet", facet);
        }
        polygon.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.push_back(v);
      }
      if (polygon.size() < 3)
        errors.at_line(in.line(), "facet " + std::to_string(facet) + " has " + std::to_string(polygon.size()) +
                                      " vertices, a facet needs at least 3");
      add_polygon(mesh, polygon.data(), polygon.size());
      expect("endfacet", "after 'endloop'");
      ++facet;
    }
    t = in.next();
  }
  return mesh;
}

}  // namespace

Mesh read_stl(std::string_view bytes, const ErrorSink& errors) {
  if (bytes.size() >= 84) {
    const std::uint32_t n = little_u32(bytes, 80);
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return read_binary_stl(bytes, n, errors);
  }
  if (bytes.size() >= 5 && std::memcmp(bytes.data(), "solid", 5) == 0) return read_ascii_stl(bytes, errors);
  // Tolerate blanks before "solid" in ASCII files.
  std::size_t i = 0;
  while (i < bytes.size() && (is_blank(bytes[i]) || bytes[i] == '\n')) ++i;
  if (i == bytes.size()) errors.whole_file("empty file");
  if (bytes.substr(i, 5) == "solid") return read_ascii_stl(bytes, errors);
  if (bytes.size() < 84) errors.at_byte(bytes.size(), "truncated: a binary STL file has at least 84 bytes, this one " + std::to_string(bytes.size()));
  const std::uint32_t n = little_u32(bytes, 80);
  const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(n);
  if (bytes.size() < expected)
    errors.at_byte(bytes.size(), "truncated: the header declares " + std::to_string(n) + " facets (" +
                                     std::to_string(expected) + " bytes), the file ends at byte " + std::to_string(bytes.size()));
  errors.at_byte(expected, "wrong counts: the header declares " + std::to_string(n) + " facets (" + std::to_string(expected) +
                               " bytes), but " + std::to_string(bytes.size() - expected) + " bytes follow them");
}

}  // namespace raykernel::io::detail
