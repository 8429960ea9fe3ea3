// write_mesh: every format, exactly (shortest round-trip decimals, binary doubles, STL floats when exact).
#include <raykernel/io/mesh_file.hpp>

#include <bit>
#include <charconv>
#include <cstring>
#include <stdexcept>

namespace raykernel::io {
namespace {

void append_number(std::string& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

void append_vec(std::string& out, const Vec3& v) {
  append_number(out, v.x);
  out += ' ';
  append_number(out, v.y);
  out += ' ';
  append_number(out, v.z);
}

template <class T>
void append_binary(std::string& out, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian == (std::endian::native == std::endian::little))
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  out.append(bytes, sizeof(T));
}

std::string write_obj(const Mesh& m) {
  std::string out = "# written by raykernel\n";
  for (const Vec3& v : m.vertices) {
    out += "v ";
    append_vec(out, v);
    out += '\n';
  }
  for (const auto& t : m.triangles)
    out += "f " + std::to_string(t[0] + 1ull) + ' ' + std::to_string(t[1] + 1ull) + ' ' + std::to_string(t[2] + 1ull) + '\n';
  return out;
}

std::string write_off(const Mesh& m) {
  std::string out = "OFF\n" + std::to_string(m.vertices.size()) + ' ' + std::to_string(m.triangles.size()) + " 0\n";
  for (const Vec3& v : m.vertices) {
    append_vec(out, v);
    out += '\n';
  }
  for (const auto& t : m.triangles)
    out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) + '\n';
  return out;
}

std::string write_ply(const Mesh& m, MeshEncoding encoding) {
  const char* format = encoding == MeshEncoding::ascii                  ? "ascii"
                       : encoding == MeshEncoding::binary_little_endian ? "binary_little_endian"
                                                                        : "binary_big_endian";
  std::string out = std::string("ply\nformat ") + format + " 1.0\ncomment written by raykernel\nelement vertex " +
                    std::to_string(m.vertices.size()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(m.triangles.size()) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  if (encoding == MeshEncoding::ascii) {
    for (const Vec3& v : m.vertices) {
      append_vec(out, v);
      out += '\n';
    }
    for (const auto& t : m.triangles)
      out += "3 " + std::to_string(t[0]) + ' ' + std::to_string(t[1]) + ' ' + std::to_string(t[2]) + '\n';
    return out;
  }
  const bool big = encoding == MeshEncoding::binary_big_endian;
  for (const Vec3& v : m.vertices) {
    append_binary(out, v.x, big);
    append_binary(out, v.y, big);
    append_binary(out, v.z, big);
  }
  for (const auto& t : m.triangles) {
    out += '\3';
    for (std::uint32_t i : t) append_binary(out, i, big);
  }
  return out;
}

std::string write_stl(const Mesh& m, MeshEncoding encoding) {
  if (encoding == MeshEncoding::ascii) {
    std::string out = "solid raykernel\n";
    for (std::size_t k = 0; k < m.triangles.size(); ++k) {
      const Triangle t = m.triangle(k);
      out += "facet normal 0 0 0\nouter loop\n";
      for (const Vec3& v : {t.a, t.b, t.c}) {
        out += "vertex ";
        append_vec(out, v);
        out += '\n';
      }
      out += "endloop\nendfacet\n";
    }
    return out + "endsolid raykernel\n";
  }
  if (encoding == MeshEncoding::binary_big_endian) throw std::invalid_argument("write_mesh: STL has no big-endian encoding");
  if (m.triangles.size() > 0xffffffffu) throw std::invalid_argument("write_mesh: too many triangles for binary STL");
  std::string out(80, ' ');
  out.replace(0, 24, "binary STL by raykernel.");
  append_binary(out, static_cast<std::uint32_t>(m.triangles.size()), false);
  for (std::size_t k = 0; k < m.triangles.size(); ++k) {
    const Triangle t = m.triangle(k);
    for (int i = 0; i < 3; ++i) append_binary(out, 0.0f, false);
    for (const Vec3& v : {t.a, t.b, t.c})
      for (double c : {v.x, v.y, v.z}) {
        const auto f = static_cast<float>(c);
        if (static_cast<double>(f) != c)
          throw std::invalid_argument("write_mesh: binary STL stores floats; a coordinate of triangle " + std::to_string(k) +
                                      " is not a float");
        append_binary(out, f, false);
      }
    append_binary(out, std::uint16_t{0}, false);
  }
  return out;
}

}  // namespace

std::string write_mesh(const Mesh& mesh, MeshFormat format, MeshEncoding encoding) {
  if (const auto problem = validate(mesh)) throw std::invalid_argument("write_mesh: " + *problem);
  switch (format) {
    case MeshFormat::obj:
    case MeshFormat::off:
      if (encoding != MeshEncoding::ascii) throw std::invalid_argument("write_mesh: OBJ and OFF are text formats");
      return format == MeshFormat::obj ? write_obj(mesh) : write_off(mesh);
    case MeshFormat::ply: return write_ply(mesh, encoding);
    case MeshFormat::stl: return write_stl(mesh, encoding);
    case MeshFormat::gltf:
      throw std::invalid_argument("write_mesh: glTF positions are float32, which cannot hold every double (write OBJ, "
                                  "PLY, OFF or STL)");
  }
  throw std::invalid_argument("write_mesh: unknown format");
}

}  // namespace raykernel::io
