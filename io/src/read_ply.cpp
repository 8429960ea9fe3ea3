// The PLY reader: `format ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`; the element
// `vertex` with scalar properties x, y, z of any type (char/int8 ... double/float64; integers are exact in
// double, floats are widened exactly); the element `face` with a list property `vertex_indices` (or
// `vertex_index`) of any integer count and index types, each polygon fanned. Every other property and
// element is skipped, in all three encodings (lists included). `comment` and `obj_info` lines are ignored.
// Header errors name the line; errors in binary data name the byte offset; ASCII data names the line (one
// element instance per line, blank lines allowed). Nothing may follow the last element but blank lines
// (ASCII) or nothing (binary).
#include "reader_support.hpp"

#include <bit>
#include <cstring>
#include <optional>
#include <unordered_set>

namespace raykernel::io::detail {
namespace {

enum class PlyType : std::uint8_t { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

std::optional<PlyType> ply_type(std::string_view name) {
  if (name == "char" || name == "int8") return PlyType::int8;
  if (name == "uchar" || name == "uint8") return PlyType::uint8;
  if (name == "short" || name == "int16") return PlyType::int16;
  if (name == "ushort" || name == "uint16") return PlyType::uint16;
  if (name == "int" || name == "int32") return PlyType::int32;
  if (name == "uint" || name == "uint32") return PlyType::uint32;
  if (name == "float" || name == "float32") return PlyType::float32;
  if (name == "double" || name == "float64") return PlyType::float64;
  return std::nullopt;
}

std::size_t size_of(PlyType t) {
  switch (t) {
    case PlyType::int8: case PlyType::uint8: return 1;
    case PlyType::int16: case PlyType::uint16: return 2;
    case PlyType::int32: case PlyType::uint32: case PlyType::float32: return 4;
    case PlyType::float64: return 8;
  }
  return 1;
}

bool is_integer(PlyType t) { return t != PlyType::float32 && t != PlyType::float64; }

std::int64_t min_of(PlyType t) {
  switch (t) {
    case PlyType::int8: return -128;
    case PlyType::int16: return -32768;
    case PlyType::int32: return -2147483648LL;
    default: return 0;
  }
}
std::int64_t max_of(PlyType t) {
  switch (t) {
    case PlyType::int8: return 127;
    case PlyType::uint8: return 255;
    case PlyType::int16: return 32767;
    case PlyType::uint16: return 65535;
    case PlyType::int32: return 2147483647LL;
    default: return 4294967295LL;
  }
}

struct Property {
  std::string name;
  bool list = false;
  PlyType count_type = PlyType::uint8;  // lists only
  PlyType type = PlyType::float32;      // the scalar's type, or the list items'
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::uint64_t header_line = 0;
  std::vector<Property> properties;
};

enum class Encoding { ascii, little, big };

// Reads binary values with bounds checks; offsets are file offsets.
class BinaryData {
 public:
  BinaryData(std::string_view bytes, std::size_t start, Encoding encoding, const ErrorSink& errors)
      : bytes_(bytes), pos_(start), big_(encoding == Encoding::big), errors_(errors) {}
  [[nodiscard]] std::size_t offset() const { return pos_; }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - pos_; }

  // The raw bits of a value of type t (sign-extended for signed integers), advancing.
  std::uint64_t raw(PlyType t, const Element& e, std::uint64_t instance) {
    const std::size_t n = size_of(t);
    if (remaining() < n)
      errors_.at_byte(pos_, "truncated: the file ends inside " + e.name + " " + std::to_string(instance));
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto byte = static_cast<unsigned char>(bytes_[pos_ + (big_ ? i : n - 1 - i)]);
      v = (v << 8) | byte;
    }
    pos_ += n;
    return v;
  }
  std::int64_t integer(PlyType t, const Element& e, std::uint64_t instance) {
    const std::uint64_t v = raw(t, e, instance);
    switch (t) {
      case PlyType::int8: return static_cast<std::int8_t>(v);
      case PlyType::int16: return static_cast<std::int16_t>(v);
      case PlyType::int32: return static_cast<std::int32_t>(v);
      default: return static_cast<std::int64_t>(v);
    }
  }
  double number(PlyType t, const Element& e, std::uint64_t instance) {
    if (t == PlyType::float32) return static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(raw(t, e, instance))));
    if (t == PlyType::float64) return std::bit_cast<double>(raw(t, e, instance));
    return static_cast<double>(integer(t, e, instance));  // |value| < 2^32: exact
  }
  void skip(std::size_t n, const Element& e, std::uint64_t instance) {
    if (remaining() < n)
      errors_.at_byte(pos_, "truncated: the file ends inside " + e.name + " " + std::to_string(instance));
    pos_ += n;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_;
  bool big_;
  const ErrorSink& errors_;
};

struct Header {
  Encoding encoding = Encoding::ascii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;
  std::uint64_t body_first_line = 0;
};

Header read_header(std::string_view bytes, const ErrorSink& errors) {
  Header h;
  LineReader lines(bytes, false);
  std::string_view line;
  if (!lines.next(line) || line != "ply") errors.at_line(1, "not a PLY file (the first line must be 'ply')");
  bool have_format = false;
  std::unordered_set<std::string> element_names;  // a header may declare many elements: no linear scan per name
  while (true) {
    if (!lines.next(line)) errors.at_line(lines.line_number() + 1, "the header has no end_header line");
    const std::uint64_t n = lines.line_number();
    Tokens tokens(line, false);
    const std::string_view keyword = tokens.next();
    if (keyword == "end_header") {
      if (!tokens.at_end()) errors.at_line(n, "unexpected text after end_header");
      if (!have_format) errors.at_line(n, "the header has no format line");
      h.body_offset = lines.offset();
      h.body_first_line = n + 1;
      return h;
    }
    if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
    if (keyword == "format") {
      const std::string_view encoding = tokens.next(), version = tokens.next();
      if (have_format) errors.at_line(n, "a second format line");
      if (encoding == "ascii") h.encoding = Encoding::ascii;
      else if (encoding == "binary_little_endian") h.encoding = Encoding::little;
      else if (encoding == "binary_big_endian") h.encoding = Encoding::big;
      else errors.at_line(n, "unknown PLY format " + quote_token(encoding));
      if (version != "1.0" || !tokens.at_end()) errors.at_line(n, "unsupported PLY version (expected 'format " + std::string(encoding) + " 1.0')");
      have_format = true;
    } else if (keyword == "element") {
      Element e;
      e.name = tokens.next();
      const std::string_view count = tokens.next();
      std::int64_t c = 0;
      if (e.name.empty() || !parse_integer(count, 0, INT64_MAX, c) || !tokens.at_end())
        errors.at_line(n, "an element line is 'element NAME COUNT' with COUNT ≥ 0");
      if (!element_names.insert(e.name).second) errors.at_line(n, "a second element named " + quote_token(e.name));
      if (e.name == "tristrips") errors.at_line(n, "triangle strips (element tristrips) are not supported");
      e.count = static_cast<std::uint64_t>(c);
      e.header_line = n;
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) errors.at_line(n, "a property before any element");
      Property p;
      std::string_view type = tokens.next();
      if (type == "list") {
        p.list = true;
        const std::string_view count_type = tokens.next();
        const auto ct = ply_type(count_type);
        if (!ct) errors.at_line(n, "unknown list count type " + quote_token(count_type));
        if (!is_integer(*ct)) errors.at_line(n, "a list count type must be an integer type, not " + quote_token(count_type));
        p.count_type = *ct;
        type = tokens.next();
      }
      const auto t = ply_type(type);
      if (!t) errors.at_line(n, "unknown property type " + quote_token(type));
      p.type = *t;
      p.name = tokens.next();
      if (p.name.empty() || !tokens.at_end()) errors.at_line(n, "a property line is 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      h.elements.back().properties.push_back(std::move(p));
    } else {
      errors.at_line(n, "unknown header line " + quote_token(keyword));
    }
  }
}

// Where the mesh's data is in the elements: the vertex element's x, y, z and the face element's index list.
struct Layout {
  const Element* vertex = nullptr;
  std::size_t coordinate[3] = {0, 0, 0};
  const Element* face = nullptr;
  std::size_t indices = 0;
};

Layout find_layout(const Header& h, const ErrorSink& errors) {
  Layout layout;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") {
      layout.vertex = &e;
      for (int axis = 0; axis < 3; ++axis) {
        const std::string name(1, static_cast<char>('x' + axis));
        bool found = false;
        for (std::size_t i = 0; i < e.properties.size() && !found; ++i)
          if (e.properties[i].name == name) {
            if (e.properties[i].list) errors.at_line(e.header_line, "vertex property " + name + " is a list");
            layout.coordinate[axis] = i;
            found = true;
          }
        if (!found) errors.at_line(e.header_line, "the vertex element has no property " + name);
      }
      if (e.count > max_vertices) errors.at_line(e.header_line, "too many vertices (meshes index with 32 bits)");
    } else if (e.name == "face") {
      layout.face = &e;
      bool found = false;
      for (std::string_view name : {"vertex_indices", "vertex_index"})
        for (std::size_t i = 0; i < e.properties.size() && !found; ++i)
          if (e.properties[i].name == name) {
            if (!e.properties[i].list || !is_integer(e.properties[i].type))
              errors.at_line(e.header_line, "face property " + std::string(name) + " must be a list of integers");
            layout.indices = i;
            found = true;
          }
      if (!found) errors.at_line(e.header_line, "the face element has no vertex_indices list");
    }
  }
  if (layout.face != nullptr && layout.face->count > 0 && layout.vertex == nullptr)
    errors.at_line(layout.face->header_line, "faces but no vertex element");
  return layout;
}

// The smallest number of bytes (binary) one instance of e occupies.
std::uint64_t min_binary_size(const Element& e) {
  std::uint64_t size = 0;
  for (const Property& p : e.properties) size += size_of(p.list ? p.count_type : p.type);
  return size;
}

void check_declared_size(const Element& e, std::uint64_t min_instance, std::uint64_t available, const ErrorSink& errors) {
  if (min_instance > 0 && e.count > available / min_instance)
    errors.at_line(e.header_line, "wrong counts: the header declares " + std::to_string(e.count) + " " + e.name +
                                      " instances (at least " + std::to_string(min_instance) + " bytes each), but only " +
                                      std::to_string(available) + " bytes of data follow");
}

Mesh read_binary(std::string_view bytes, const Header& h, const Layout& layout, const ErrorSink& errors) {
  Mesh mesh;
  BinaryData data(bytes, h.body_offset, h.encoding, errors);
  const std::uint64_t vertex_count = layout.vertex != nullptr ? layout.vertex->count : 0;
  std::vector<std::uint32_t> polygon;
  for (const Element& e : h.elements) {
    if (e.properties.empty()) continue;  // an element without properties has no data
    check_declared_size(e, min_binary_size(e), data.remaining(), errors);
    const bool is_vertex = &e == layout.vertex, is_face = &e == layout.face;
    if (is_vertex) mesh.vertices.resize(e.count);
    for (std::uint64_t k = 0; k < e.count; ++k) {
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        const std::size_t at = data.offset();
        if (!p.list) {
          if (is_vertex && (i == layout.coordinate[0] || i == layout.coordinate[1] || i == layout.coordinate[2])) {
            const double value = data.number(p.type, e, k);
            check_finite_at_byte(errors, at, value, p.name + " of vertex " + std::to_string(k));
            Vec3& v = mesh.vertices[k];
            if (i == layout.coordinate[0]) v.x = value;
            if (i == layout.coordinate[1]) v.y = value;
            if (i == layout.coordinate[2]) v.z = value;
          } else {
            data.skip(size_of(p.type), e, k);
          }
          continue;
        }
        const std::int64_t count = data.integer(p.count_type, e, k);
        if (count < 0) errors.at_byte(at, "negative list length " + std::to_string(count) + " in " + e.name + " " + std::to_string(k));
        const auto items = static_cast<std::uint64_t>(count);
        if (items > data.remaining() / size_of(p.type))
          errors.at_byte(at, "truncated: the list of " + std::to_string(items) + " items in " + e.name + " " +
                                 std::to_string(k) + " runs past the end of the file");
        if (!(is_face && i == layout.indices)) {
          data.skip(items * size_of(p.type), e, k);
          continue;
        }
        if (items < 3) errors.at_byte(at, "face " + std::to_string(k) + " has " + std::to_string(items) + " vertices, a face needs at least 3");
        polygon.clear();
        for (std::uint64_t j = 0; j < items; ++j) {
          const std::size_t index_at = data.offset();
          const std::int64_t index = data.integer(p.type, e, k);
          if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count)
            errors.at_byte(index_at, "vertex index " + std::to_string(index) + " of face " + std::to_string(k) +
                                         " is out of range (" + count_of(vertex_count, "vertex", "vertices") + ")");
          polygon.push_back(static_cast<std::uint32_t>(index));
        }
        add_polygon(mesh, polygon.data(), polygon.size());
      }
    }
  }
  if (data.remaining() != 0)
    errors.at_byte(data.offset(), "wrong counts: " + std::to_string(data.remaining()) + " bytes follow the last element");
  return mesh;
}

Mesh read_ascii(std::string_view bytes, const Header& h, const Layout& layout, const ErrorSink& errors) {
  Mesh mesh;
  LineReader lines(bytes.substr(h.body_offset), false);
  const std::uint64_t first_line = h.body_first_line;
  const std::uint64_t vertex_count = layout.vertex != nullptr ? layout.vertex->count : 0;
  std::vector<std::uint32_t> polygon;
  std::string_view line;
  auto line_number = [&] { return first_line + lines.line_number() - 1; };
  for (const Element& e : h.elements) {
    if (e.properties.empty()) continue;  // an element without properties has no data
    // Each instance takes at least a value and a line end.
    const std::uint64_t available = bytes.size() - h.body_offset;
    if (e.count > available / 2)
      errors.at_line(e.header_line, "wrong counts: the header declares " + std::to_string(e.count) + " " + e.name +
                                        " instances, more than the " + std::to_string(available) + " bytes of data can hold");
    const bool is_vertex = &e == layout.vertex, is_face = &e == layout.face;
    if (is_vertex) mesh.vertices.resize(e.count);
    for (std::uint64_t k = 0; k < e.count; ++k) {
      do {
        if (!lines.next(line))
          errors.at_line(line_number() + 1, "truncated: the file ends before " + e.name + " " + std::to_string(k) +
                                               " (the header declares " + std::to_string(e.count) + ")");
      } while (only_whitespace(line));
      const std::uint64_t n = line_number();
      Tokens tokens(line, false);
      auto value_of = [&](const Property& p) {
        const std::string_view t = tokens.next();
        if (t.empty()) errors.at_line(n, "wrong counts: " + e.name + " " + std::to_string(k) + " has no value for " + p.name);
        return t;
      };
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        const Property& p = e.properties[i];
        if (!p.list) {
          const std::string_view t = value_of(p);
          const int axis = !is_vertex ? -1 : i == layout.coordinate[0] ? 0 : i == layout.coordinate[1] ? 1 : i == layout.coordinate[2] ? 2 : -1;
          std::int64_t integer = 0;
          if (is_integer(p.type)) {
            if (!parse_integer(t, min_of(p.type), max_of(p.type), integer))
              errors.at_line(n, p.name + " of " + e.name + " " + std::to_string(k) + ": " + quote_token(t) + " is not an integer of its type");
            if (axis >= 0) (&mesh.vertices[k].x)[axis] = static_cast<double>(integer);
          } else if (axis >= 0) {
            (&mesh.vertices[k].x)[axis] = coordinate_at_line(errors, n, t, static_cast<char>('x' + axis), "vertex", k);
          } else if (parse_double(t).error == NumberError::not_a_number) {
            errors.at_line(n, p.name + " of " + e.name + " " + std::to_string(k) + ": " + quote_token(t) + " is not a number");
          }
          continue;
        }
        const std::string_view count_text = value_of(p);
        std::int64_t count = 0;
        if (!parse_integer(count_text, 0, max_of(p.count_type), count))
          errors.at_line(n, "list length of " + p.name + " in " + e.name + " " + std::to_string(k) + ": " + quote_token(count_text) +
                                " is not a count of its type");
        const bool indices = is_face && i == layout.indices;
        if (indices && count < 3)
          errors.at_line(n, "face " + std::to_string(k) + " has " + std::to_string(count) + " vertices, a face needs at least 3");
        if (indices) polygon.clear();
        for (std::int64_t j = 0; j < count; ++j) {
          const std::string_view t = value_of(p);
          std::int64_t value = 0;
          if (is_integer(p.type)) {
            if (!parse_integer(t, min_of(p.type), max_of(p.type), value))
              errors.at_line(n, "item " + std::to_string(j) + " of " + p.name + " in " + e.name + " " + std::to_string(k) + ": " +
                                    quote_token(t) + " is not an integer of its type");
          } else if (parse_double(t).error == NumberError::not_a_number) {
            errors.at_line(n, "item " + std::to_string(j) + " of " + p.name + " in " + e.name + " " + std::to_string(k) + ": " +
                                  quote_token(t) + " is not a number");
          }
          if (indices) {
            if (value < 0 || static_cast<std::uint64_t>(value) >= vertex_count)
              errors.at_line(n, "vertex index " + std::to_string(value) + " of face " + std::to_string(k) + " is out of range (" +
                                    count_of(vertex_count, "vertex", "vertices") + ")");
            polygon.push_back(static_cast<std::uint32_t>(value));
          }
        }
        if (indices) add_polygon(mesh, polygon.data(), polygon.size());
      }
      if (!tokens.at_end())
        errors.at_line(n, "wrong counts: " + e.name + " " + std::to_string(k) + " has more values than its properties");
    }
  }
  while (lines.next(line))
    if (!only_whitespace(line)) errors.at_line(line_number(), "wrong counts: text follows the last element");
  return mesh;
}

}  // namespace

Mesh read_ply(std::string_view bytes, const ErrorSink& errors) {
  const Header h = read_header(bytes, errors);
  const Layout layout = find_layout(h, errors);
  return h.encoding == Encoding::ascii ? read_ascii(bytes, h, layout, errors) : read_binary(bytes, h, layout, errors);
}

}  // namespace raykernel::io::detail
