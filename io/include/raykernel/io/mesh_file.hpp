// raykernel/io/mesh_file.hpp: triangle meshes from the files people have — OBJ, PLY, STL, OFF, glTF — exactly.
//
// docs/contract.md §7: a mesh is its vertices, as the doubles the file states, and its triangles, as vertex
// indices counted from 0 in file order; a polygon with k > 3 vertices becomes the k − 2 triangles
// (v0, v_i, v_{i+1}) fanned from its first vertex, in order. Binary floats are widened to double exactly;
// decimal (and hexadecimal) text is read with correct rounding (<raykernel/io/number.hpp>). Nothing is
// welded, moved or dropped: an STL facet adds its own three vertices, degenerate triangles are kept.
//
// A file that cannot be read as a mesh throws `mesh_file_error`, naming the file, the line (text) or byte
// offset (binary data) and the reason; nothing is half-loaded. Reasons: unknown format, empty file, bad
// syntax, wrong counts, truncated data, an index out of range (0 in OBJ included), a face with fewer than 3
// vertices, a coordinate that is NaN or infinite, overflows or is a nonzero value that rounds to zero.
//
// What each reader accepts is listed in README.md, "Mesh files". The readers are written here rather than
// taken from a library because none we could use keeps the coordinates exact (README.md says which).
#pragma once

#include <raykernel/mesh.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace raykernel::io {

enum class MeshFormat : std::uint8_t { obj, ply, stl, off, gltf };  // gltf: .gltf (JSON) and .glb (binary)

// "obj", "ply", "stl", "off", "gltf".
[[nodiscard]] std::string_view to_string(MeshFormat format) noexcept;

// Where in a file something is: a line (counted from 1) of text, or a byte offset (from 0) into binary data,
// or nowhere in particular (an empty or unreadable file, an unknown format).
struct FilePosition {
  enum class Kind : std::uint8_t { none, line, byte_offset };
  Kind kind = Kind::none;
  std::uint64_t value = 0;
};

// The error of every reader. what() is "FILE:LINE: REASON", "FILE: byte OFFSET: REASON" or "FILE: REASON".
class mesh_file_error : public std::runtime_error {
 public:
  mesh_file_error(std::string file, FilePosition position, std::string reason);
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const FilePosition& position() const noexcept { return position_; }
  [[nodiscard]] const std::string& reason() const noexcept { return reason_; }

 private:
  std::string file_;
  FilePosition position_;
  std::string reason_;
};

// The format a file name's extension names (.obj, .ply, .stl, .off, .gltf, .glb, any case), or nothing.
[[nodiscard]] std::optional<MeshFormat> format_from_extension(const std::filesystem::path& path);

// The format the bytes look like, or nothing: "glTF" first (the GLB magic), or a JSON object with an "asset"
// member → glTF; "ply" and an end of line first → PLY; "OFF" (or COFF, NOFF,
// CNOFF, STOFF, ...) first → OFF; a binary STL's exact size 84 + 50·n → STL (even when its header starts
// with "solid"); "solid" first → STL; otherwise the first statement of an OBJ file (v, vt, vn, f, o, g, #,
// ...) → OBJ.
[[nodiscard]] std::optional<MeshFormat> sniff_format(std::string_view bytes) noexcept;

// Reads the mesh in the file at `path`: the format is the extension's, or else the content's (sniff_format).
// The error names the file as `path` is written. Throws mesh_file_error (also when the file cannot be
// opened or read, with the system's reason). A .gltf file's external buffers are read from its folder.
[[nodiscard]] Mesh read_mesh(const std::filesystem::path& path);

// Reads `bytes` as a mesh in `format`; `name` is the file name errors carry. A glTF's external buffers are
// refused here (only data: URIs and the GLB binary chunk): there is no folder to read them from.
[[nodiscard]] Mesh read_mesh(std::string_view bytes, std::string_view name, MeshFormat format);

// ---------------------------------------------------------------------------------------------------------
// Writing (for round trips in tests and fuzzing, and for converting): every format, exactly.
//
// Text formats print each coordinate as the shortest decimal that reads back as the same double (std::
// to_chars), so read_mesh(write_mesh(m)) == m bit for bit. PLY binary stores doubles (property double x);
// STL stores floats, so STL binary can only be written when every coordinate is a float exactly (else
// std::invalid_argument). STL, having no indices, writes each triangle's three vertices: reading it back
// gives the same triangles with unshared vertices.
enum class MeshEncoding : std::uint8_t { ascii, binary_little_endian, binary_big_endian };

// Throws std::invalid_argument when `encoding` is binary and the format has none (OBJ, OFF), big-endian for
// STL, or an STL binary coordinate is not a float; and when validate(mesh) fails.
[[nodiscard]] std::string write_mesh(const Mesh& mesh, MeshFormat format, MeshEncoding encoding = MeshEncoding::ascii);

}  // namespace raykernel::io
