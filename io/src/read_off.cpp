// The OFF reader (Geomview's Object File Format, ASCII): the keyword OFF — with any of the prefixes ST, C, N
// that add per-vertex texture coordinates, colours or normals — then `nv nf [ne]` (on the keyword's line or
// the next), nv vertex lines `x y z [extra values]` and nf face lines `k i1 ... ik [colour]`, indices from
// 0, each polygon fanned. Values after a vertex's x y z and after a face's k indices are ignored but must
// be numbers. '#' starts a comment; blank lines are skipped. The 4OFF / nOFF (other dimensions) and binary
// variants are not supported.
#include "reader_support.hpp"

#include <cctype>

namespace raykernel::io::detail {

Mesh read_off(std::string_view bytes, const ErrorSink& errors) {
  Mesh mesh;
  LineReader lines(bytes, false);
  std::string_view line;
  // The next line with a token, positioned at its first token; false at the end.
  auto next_content = [&](Tokens& tokens, std::string_view& first) {
    while (lines.next(line)) {
      tokens = Tokens(line, true);
      first = tokens.next();
      if (!first.empty()) return true;
    }
    return false;
  };
  Tokens tokens("", true);
  std::string_view keyword;
  if (!next_content(tokens, keyword)) {
    if (only_whitespace(bytes)) errors.whole_file("empty file");
    errors.whole_file("no OFF header (only comments)");
  }
  // Strip a UTF-8 byte-order mark.
  if (lines.line_number() == 1 && keyword.substr(0, 3) == "\xEF\xBB\xBF") keyword.remove_prefix(3);
  std::string_view k = keyword;
  if (k.substr(0, 2) == "ST") k.remove_prefix(2);
  if (!k.empty() && k.front() == 'C') k.remove_prefix(1);
  if (!k.empty() && k.front() == 'N') k.remove_prefix(1);
  if (!k.empty() && (k.front() == '4' || k.front() == 'n'))
    errors.at_line(lines.line_number(), quote_token(keyword) + ": OFF files of other dimensions than 3 are not supported");
  if (k != "OFF") errors.at_line(lines.line_number(), "expected the OFF keyword, found " + quote_token(keyword));
  std::string_view count_token = tokens.next();
  if (count_token == "BINARY") errors.at_line(lines.line_number(), "binary OFF files are not supported");
  if (count_token.empty() && !next_content(tokens, count_token))
    errors.at_line(lines.line_number() + 1, "truncated: the file ends before the vertex and face counts");
  const std::uint64_t counts_line = lines.line_number();
  std::int64_t nv = 0, nf = 0, ne = 0;
  const std::string_view faces_token = tokens.next(), edges_token = tokens.next();
  if (!parse_integer(count_token, 0, static_cast<std::int64_t>(max_vertices), nv) || !parse_integer(faces_token, 0, INT64_MAX, nf) ||
      (!edges_token.empty() && !parse_integer(edges_token, 0, INT64_MAX, ne)) || !tokens.at_end())
    errors.at_line(counts_line, "expected the counts 'vertices faces [edges]' (integers ≥ 0, fewer than 2^32 vertices)");
  // Every vertex and face takes at least 6 bytes ("0 0 0\n", "3 0 0 0\n" is more).
  const std::uint64_t rest = bytes.size() - lines.offset();
  if (static_cast<std::uint64_t>(nv) > rest / 6 || static_cast<std::uint64_t>(nf) > rest / 6)
    errors.at_line(counts_line, "wrong counts: " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                                    " faces do not fit in the " + std::to_string(rest) + " bytes that follow");
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  std::string_view first;
  for (std::int64_t i = 0; i < nv; ++i) {
    if (!next_content(tokens, first))
      errors.at_line(lines.line_number() + 1, "truncated: the file ends before vertex " + std::to_string(i) + " (the header declares " +
                                                  std::to_string(nv) + ")");
    const std::uint64_t n = lines.line_number();
    const auto index = static_cast<std::uint64_t>(i);
    Vec3 v{};
    v.x = coordinate_at_line(errors, n, first, 'x', "vertex", index);
    v.y = coordinate_at_line(errors, n, tokens.next(), 'y', "vertex", index);
    v.z = coordinate_at_line(errors, n, tokens.next(), 'z', "vertex", index);
    for (std::string_view t = tokens.next(); !t.empty(); t = tokens.next())
      if (parse_double(t).error == NumberError::not_a_number)
        errors.at_line(n, "vertex " + std::to_string(i) + ": " + quote_token(t) + " is not a number");
    mesh.vertices.push_back(v);
  }
  std::vector<std::uint32_t> polygon;
  for (std::int64_t f = 0; f < nf; ++f) {
    if (!next_content(tokens, first))
      errors.at_line(lines.line_number() + 1, "truncated: the file ends before face " + std::to_string(f) + " (the header declares " +
                                                  std::to_string(nf) + ")");
    const std::uint64_t n = lines.line_number();
    std::int64_t count = 0;
    if (!parse_integer(first, 0, INT64_MAX, count))
      errors.at_line(n, "face " + std::to_string(f) + ": the vertex count " + quote_token(first) + " is not an integer ≥ 0");
    if (count < 3)
      errors.at_line(n, "face " + std::to_string(f) + " has " + std::to_string(count) + " vertices, a face needs at least 3");
    polygon.clear();
    for (std::int64_t j = 0; j < count; ++j) {
      const std::string_view t = tokens.next();
      std::int64_t index = 0;
      if (t.empty())
        errors.at_line(n, "wrong counts: face " + std::to_string(f) + " declares " + std::to_string(count) + " vertices but lists " +
                              std::to_string(j));
      if (!parse_integer(t, INT64_MIN, INT64_MAX, index))
        errors.at_line(n, "face " + std::to_string(f) + ": " + quote_token(t) + " is not a vertex index");
      if (index < 0 || index >= nv)
        errors.at_line(n, "vertex index " + std::to_string(index) + " of face " + std::to_string(f) + " is out of range (" +
                              count_of(static_cast<std::uint64_t>(nv), "vertex", "vertices") + ")");
      polygon.push_back(static_cast<std::uint32_t>(index));
    }
    int extra = 0;
    for (std::string_view t = tokens.next(); !t.empty(); t = tokens.next(), ++extra) {
      if (extra == 4 || parse_double(t).error == NumberError::not_a_number)
        errors.at_line(n, "face " + std::to_string(f) + ": after its " + std::to_string(count) +
                              " indices a face may have a colour (at most 4 numbers), found " + quote_token(t));
    }
    add_polygon(mesh, polygon.data(), polygon.size());
  }
  while (next_content(tokens, first))
    errors.at_line(lines.line_number(), "wrong counts: " + quote_token(first) + " follows the last face");
  return mesh;
}

}  // namespace raykernel::io::detail
