// read_mesh, format detection, the error type and the shared helpers of the readers.
#include "reader_support.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace raykernel::io {
namespace {

std::string error_message(const std::string& file, const FilePosition& p, const std::string& reason) {
  std::string m = file;
  switch (p.kind) {
    case FilePosition::Kind::line: m.append(":").append(std::to_string(p.value)).append(": "); break;
    case FilePosition::Kind::byte_offset: m.append(": byte ").append(std::to_string(p.value)).append(": "); break;
    case FilePosition::Kind::none: m.append(": "); break;
  }
  return m.append(reason);
}

bool starts_with_word(std::string_view text, std::string_view word) {
  if (text.substr(0, word.size()) != word) return false;
  return text.size() == word.size() || detail::is_blank(text[word.size()]) || text[word.size()] == '\n';
}

}  // namespace

mesh_file_error::mesh_file_error(std::string file, FilePosition position, std::string reason)
    : std::runtime_error(error_message(file, position, reason)),
      file_(std::move(file)),
      position_(position),
      reason_(std::move(reason)) {}

std::string_view to_string(MeshFormat format) noexcept {
  switch (format) {
    case MeshFormat::obj: return "obj";
    case MeshFormat::ply: return "ply";
    case MeshFormat::stl: return "stl";
    case MeshFormat::off: return "off";
    case MeshFormat::gltf: return "gltf";
  }
  return "?";
}

std::optional<MeshFormat> format_from_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](char c) { return c >= 'A' && c <= 'Z' ? char(c - 'A' + 'a') : c; });
  if (ext == ".obj") return MeshFormat::obj;
  if (ext == ".ply") return MeshFormat::ply;
  if (ext == ".stl") return MeshFormat::stl;
  if (ext == ".off") return MeshFormat::off;
  if (ext == ".gltf" || ext == ".glb") return MeshFormat::gltf;
  return std::nullopt;
}

std::optional<MeshFormat> sniff_format(std::string_view bytes) noexcept {
  if (bytes.substr(0, 4) == "glTF") return MeshFormat::gltf;  // the GLB header's magic
  if (bytes.substr(0, 4) == "ply\n" || bytes.substr(0, 5) == "ply\r\n") return MeshFormat::ply;
  if (bytes.size() >= 84) {
    std::uint32_t n = 0;
    for (int i = 3; i >= 0; --i) n = (n << 8) | static_cast<unsigned char>(bytes[80 + static_cast<std::size_t>(i)]);
    if (bytes.size() == 84 + 50 * static_cast<std::uint64_t>(n)) return MeshFormat::stl;
  }
  // Skip blanks and blank lines (and a UTF-8 byte-order mark) before looking at the first word.
  std::size_t i = bytes.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  while (i < bytes.size() && (detail::is_blank(bytes[i]) || bytes[i] == '\n')) ++i;
  const std::string_view text = bytes.substr(i);
  // [ST][C][N][4][n]OFF
  std::size_t k = 0;
  if (text.substr(0, 2) == "ST") k = 2;
  if (k < text.size() && text[k] == 'C') ++k;
  if (k < text.size() && text[k] == 'N') ++k;
  if (k < text.size() && text[k] == '4') ++k;
  if (k < text.size() && text[k] == 'n') ++k;
  if (text.substr(k, 3) == "OFF" && (text.size() == k + 3 || !std::isalpha(static_cast<unsigned char>(text[k + 3]))))
    return MeshFormat::off;
  if (starts_with_word(text, "solid")) return MeshFormat::stl;
  for (std::string_view word : {"v", "vt", "vn", "vp", "f", "o", "g", "s", "l", "p", "usemtl", "mtllib"})
    if (starts_with_word(text, word)) return MeshFormat::obj;
  if (!text.empty() && text[0] == '#') return MeshFormat::obj;  // OBJ files commonly start with a comment
  if (!text.empty() && text[0] == '{' && text.find("\"asset\"") != std::string_view::npos) return MeshFormat::gltf;
  return std::nullopt;
}

Mesh read_mesh(std::string_view bytes, std::string_view name, MeshFormat format) {
  const detail::ErrorSink errors(name);
  if (bytes.empty()) errors.whole_file("empty file");
  switch (format) {
    case MeshFormat::obj: return detail::read_obj(bytes, errors);
    case MeshFormat::ply: return detail::read_ply(bytes, errors);
    case MeshFormat::stl: return detail::read_stl(bytes, errors);
    case MeshFormat::off: return detail::read_off(bytes, errors);
    case MeshFormat::gltf: return detail::read_gltf(bytes, errors, nullptr);
  }
  errors.whole_file("unknown format");
}

Mesh read_mesh(const std::filesystem::path& path) {
  const std::string name = path.string();
  const detail::ErrorSink errors(name);
  // The system's calls end a name at its first NUL: "a.off\0x" would read a.off. Refuse it.
  if (name.find('\0') != std::string::npos) errors.whole_file("the file name contains a NUL character, which no file name can hold");
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status)) errors.whole_file("is a directory");
  // A device (/dev/zero, a terminal) would be read without end; pipes and regular files are read whole.
  if (std::filesystem::is_character_file(status) || std::filesystem::is_block_file(status) ||
      std::filesystem::is_socket(status))
    errors.whole_file("is a device or socket, not a mesh file");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(name.c_str(), "rb"), &std::fclose);
  if (!file) errors.whole_file(std::string("cannot open: ") + std::strerror(errno));
  std::string bytes;
  char buffer[1 << 16];
  while (true) {
    const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
    bytes.append(buffer, n);
    if (n < sizeof buffer) break;
  }
  if (std::ferror(file.get())) errors.whole_file(std::string("cannot read: ") + std::strerror(errno));
  std::optional<MeshFormat> format = format_from_extension(path);
  if (!format) {
    if (bytes.empty()) errors.whole_file("empty file");
    format = sniff_format(bytes);
  }
  if (!format) errors.whole_file("unknown format (not OBJ, PLY, STL, OFF or glTF by its extension or content)");
  if (*format == MeshFormat::gltf) {  // external buffers next to the file
    if (bytes.empty()) errors.whole_file("empty file");
    const std::filesystem::path folder = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
    return detail::read_gltf(bytes, errors, &folder);
  }
  return read_mesh(bytes, name, *format);
}

namespace detail {

void ErrorSink::at_line(std::uint64_t line, const std::string& reason) const {
  throw mesh_file_error(std::string(file_), {FilePosition::Kind::line, line}, reason);
}
void ErrorSink::at_byte(std::uint64_t offset, const std::string& reason) const {
  throw mesh_file_error(std::string(file_), {FilePosition::Kind::byte_offset, offset}, reason);
}
void ErrorSink::whole_file(const std::string& reason) const {
  throw mesh_file_error(std::string(file_), {}, reason);
}

std::string quote_token(std::string_view token) {
  std::string out = "'";
  const std::size_t shown = std::min<std::size_t>(token.size(), 40);
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c < 0x20 || c >= 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (shown < token.size()) out += "...";
  return out + "'";
}

bool only_whitespace(std::string_view text) noexcept {
  return std::all_of(text.begin(), text.end(), [](char c) { return is_blank(c) || c == '\n'; });
}

void bad_coordinate(const ErrorSink& errors, std::uint64_t line, std::string_view token, char axis,
                    std::string_view element, std::uint64_t index, NumberError error) {
  const std::string what = std::string(1, axis) + " of " + std::string(element) + " " + std::to_string(index);
  if (token.empty()) errors.at_line(line, what + " is missing");
  errors.at_line(line, what + ": " + quote_token(token) + " " + std::string(describe(error)));
}

std::string count_of(std::uint64_t n, std::string_view singular, std::string_view plural) {
  return std::to_string(n) + " " + std::string(n == 1 ? singular : plural);
}

std::string_view LineReader::physical_line() {
  const std::size_t start = pos_;
  const std::size_t end = text_.find('\n', start);
  std::string_view line;
  if (end == std::string_view::npos) {
    line = text_.substr(start);
    pos_ = text_.size();
  } else {
    line = text_.substr(start, end - start);
    pos_ = end + 1;
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  line_number_ = next_line_number_++;
  line = physical_line();
  if (!continuations_ || line.empty() || line.back() != '\\') return true;
  joined_.assign(line.substr(0, line.size() - 1));
  while (pos_ < text_.size()) {
    ++next_line_number_;
    std::string_view more = physical_line();
    const bool continued = !more.empty() && more.back() == '\\';
    if (continued) more.remove_suffix(1);
    joined_ += ' ';
    joined_ += more;
    if (!continued) break;
  }
  line = joined_;
  return true;
}

}  // namespace detail
}  // namespace raykernel::io
