// fuzz_mesh_reader: arbitrary bytes as a mesh file, through every reader of <raykernel/io/mesh_file.hpp>.
//
// The input is read five times, as OBJ, PLY, STL, OFF and glTF (read_mesh with an explicit format; glTF from
// memory: JSON or GLB, data: URIs only, through tinygltf when it was found at configure time). Checked:
//   - a reader either returns a mesh or throws mesh_file_error — nothing else, no crash, no sanitizer report
//     — and the error names the file given, has a reason, and a position inside the input: a line between 1
//     and the number of lines + 1, or a byte offset ≤ the input's size;
//   - a mesh it returns is valid, decided from the bits (every coordinate finite, every index < the vertex
//     count), and its triangles are what the readers promise: for OBJ read without line continuations, the
//     `v` lines' first three tokens read by strtod are the vertices, bit for bit, in order, and the `f` lines'
//     references, resolved in 128-bit integers and fanned, are the triangles;
//   - round trips: the mesh written as OBJ, OFF, PLY (ASCII, binary little- and big-endian) and read back is
//     the same mesh bit for bit; written as ASCII STL and read back, the same triangles with unshared
//     vertices; and, when every coordinate is a float, the same through binary STL;
//   - sniff_format never crashes, and when it names a format, that reader is the one read_mesh(path) uses
//     (checked through the in-memory reader: same outcome).
#include "fuzz_support.hpp"
#include "fuzz_text.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace {

using raykernel::Mesh;
using raykernel::fuzz::check;
namespace io = raykernel::io;

std::string_view current_input;

std::string describe_current() {
  return "mesh file (" + std::to_string(current_input.size()) + " bytes, C-escaped):\n" +
         raykernel::fuzz::c_escaped(current_input.substr(0, 2000));
}

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

bool same_mesh(const Mesh& a, const Mesh& b) {
  if (a.vertices.size() != b.vertices.size() || a.triangles != b.triangles) return false;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if (bits(a.vertices[i].x) != bits(b.vertices[i].x) || bits(a.vertices[i].y) != bits(b.vertices[i].y) ||
        bits(a.vertices[i].z) != bits(b.vertices[i].z))
      return false;
  return true;
}

Mesh unshared(const Mesh& m) {
  Mesh u;
  for (std::size_t k = 0; k < m.triangles.size(); ++k) {
    const raykernel::Triangle t = m.triangle(k);
    u.vertices.insert(u.vertices.end(), {t.a, t.b, t.c});
    const auto f = static_cast<std::uint32_t>(3 * k);
    u.triangles.push_back({f, f + 1, f + 2});
  }
  return u;
}

std::size_t line_count(std::string_view s) {
  std::size_t n = 1;
  for (char c : s) n += c == '\n';
  return n;
}

void check_obj_vertices(const Mesh& m, std::string_view text) {
  if (text.find('\\') != std::string_view::npos) return;  // continuations: the simple reading below does not apply
  std::size_t v = 0;
  for (std::string_view line : raykernel::fuzz::getline_lines(text)) {
    const auto tokens = raykernel::fuzz::tokens_of(line);
    if (tokens.empty() || tokens[0] != "v") continue;
    check(v < m.vertices.size(), "OBJ: more v lines than vertices");
    check(tokens.size() >= 4, "OBJ: a v line with fewer than 3 values was accepted");
    const double expected[3] = {std::strtod(std::string(tokens[1]).c_str(), nullptr), std::strtod(std::string(tokens[2]).c_str(), nullptr),
                                std::strtod(std::string(tokens[3]).c_str(), nullptr)};
    const double got[3] = {m.vertices[v].x, m.vertices[v].y, m.vertices[v].z};
    for (int a = 0; a < 3; ++a)
      check(bits(expected[a]) == bits(got[a]), [&] {
        return "OBJ: vertex " + std::to_string(v) + " coordinate " + std::to_string(a) + " is " + raykernel::fuzz::hex(got[a]) +
               ", strtod reads " + std::string(tokens[static_cast<std::size_t>(a) + 1]) + " as " + raykernel::fuzz::hex(expected[a]);
      });
    ++v;
  }
  check(v == m.vertices.size(), "OBJ: fewer v lines than vertices");
}

// The integer a face reference's vertex part denotes, in 128 bits (no 64-bit reference overflows it), or
// false when it is not one: [+]digits or -digits, at most 38 digits.
bool reference_value(std::string_view text, __int128& value) {
  if (text.empty()) return false;
  const bool negative = text[0] == '-';
  if (text[0] == '-' || text[0] == '+') text.remove_prefix(1);
  if (text.empty() || text.size() > 38) return false;
  value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    value = value * 10 + (c - '0');
  }
  if (negative) value = -value;
  return true;
}

// The triangles an accepted OBJ file must have, worked out independently of the reader (in 128-bit integers,
// so that no index wraps): each `f` line's vertex references, relative ones against the `v` lines before it,
// fanned from the first. Regression: `f 1 2 -9223372036854775808` with a vertex after it was read as the
// triangle [0, 1, 3]; the index checks above could not see it.
void check_obj_faces(const Mesh& m, std::string_view text) {
  if (text.find('\\') != std::string_view::npos) return;  // continuations: the simple reading below does not apply
  std::vector<std::array<std::uint32_t, 3>> expected;
  __int128 vertices_so_far = 0;
  for (std::string_view line : raykernel::fuzz::getline_lines(text)) {
    const auto tokens = raykernel::fuzz::tokens_of(line);
    if (tokens.empty()) continue;
    if (tokens[0] == "v") ++vertices_so_far;
    if (tokens[0] != "f") continue;
    std::vector<__int128> polygon;
    for (std::size_t k = 1; k < tokens.size() && tokens[k][0] != '#'; ++k) {
      __int128 value = 0;
      check(reference_value(tokens[k].substr(0, tokens[k].find('/')), value), [&] {
        return "OBJ: an accepted face has the reference " + std::string(tokens[k]);
      });
      const __int128 index = value < 0 ? vertices_so_far + value : value - 1;
      check(index >= 0 && index < static_cast<__int128>(m.vertices.size()),
            [&] { return "OBJ: the face reference " + std::string(tokens[k]) + " is out of range, but the file was accepted"; });
      polygon.push_back(index);
    }
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
      expected.push_back({static_cast<std::uint32_t>(polygon[0]), static_cast<std::uint32_t>(polygon[i]),
                          static_cast<std::uint32_t>(polygon[i + 1])});
  }
  check(expected == m.triangles, "OBJ: the triangles are not the fanned faces of the f lines");
}

void round_trip(const Mesh& m, std::string_view format_name) {
  using io::MeshEncoding;
  using io::MeshFormat;
  for (const auto& target : {std::pair{MeshFormat::obj, MeshEncoding::ascii}, {MeshFormat::off, MeshEncoding::ascii},
                             {MeshFormat::ply, MeshEncoding::ascii}, {MeshFormat::ply, MeshEncoding::binary_little_endian},
                             {MeshFormat::ply, MeshEncoding::binary_big_endian}}) {
    const MeshFormat format = target.first;
    const MeshEncoding encoding = target.second;
    Mesh back;
    try {
      back = io::read_mesh(io::write_mesh(m, format, encoding), "round-trip", format);
    } catch (const std::exception& e) {
      check(false, [&] { return std::string(format_name) + " -> " + std::string(io::to_string(format)) + ": " + e.what(); });
    }
    check(same_mesh(m, back), [&] { return std::string(format_name) + " -> " + std::string(io::to_string(format)) + ": not the same mesh"; });
  }
  const Mesh u = unshared(m);
  check(same_mesh(u, io::read_mesh(io::write_mesh(m, MeshFormat::stl), "round-trip", MeshFormat::stl)),
        [&] { return std::string(format_name) + " -> ASCII STL: not the same triangles"; });
  bool floats = true;
  for (const auto& v : u.vertices)
    for (double c : {v.x, v.y, v.z}) floats = floats && static_cast<double>(static_cast<float>(c)) == c;
  if (floats)
    check(same_mesh(u, io::read_mesh(io::write_mesh(m, MeshFormat::stl, MeshEncoding::binary_little_endian), "round-trip", MeshFormat::stl)),
          [&] { return std::string(format_name) + " -> binary STL: not the same triangles"; });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  raykernel::fuzz::set_harness_name("mesh_reader");
  raykernel::fuzz::set_input_describer(describe_current);
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  current_input = input;
  for (io::MeshFormat format :
       {io::MeshFormat::obj, io::MeshFormat::ply, io::MeshFormat::stl, io::MeshFormat::off, io::MeshFormat::gltf}) {
    const std::string_view name = io::to_string(format);
    Mesh mesh;
    try {
      mesh = io::read_mesh(input, "fuzz-input", format);
    } catch (const io::mesh_file_error& e) {
      check(e.file() == "fuzz-input", [&] { return std::string(name) + ": the error names " + e.file(); });
      check(!e.reason().empty(), [&] { return std::string(name) + ": an error without a reason"; });
      const auto& p = e.position();
      if (p.kind == io::FilePosition::Kind::line)
        check(p.value >= 1 && p.value <= line_count(input) + 1, [&] { return std::string(name) + ": line " + std::to_string(p.value) + " of " + e.what(); });
      if (p.kind == io::FilePosition::Kind::byte_offset)
        check(p.value <= size, [&] { return std::string(name) + ": byte offset outside the input: " + e.what(); });
      continue;
    } catch (const std::exception& e) {
      check(false, [&] { return std::string(name) + ": threw something other than mesh_file_error: " + e.what(); });
    }
    for (const auto& v : mesh.vertices)
      check(raykernel::fuzz::finite_vector_by_bits(v), [&] { return std::string(name) + ": a non-finite coordinate was accepted"; });
    for (const auto& t : mesh.triangles)
      for (std::uint32_t i : t) check(i < mesh.vertices.size(), [&] { return std::string(name) + ": an index out of range was accepted"; });
    if (format == io::MeshFormat::obj) {
      check_obj_vertices(mesh, input);
      check_obj_faces(mesh, input);
    }
    round_trip(mesh, name);
  }
  (void)io::sniff_format(input);
  return 0;
}
