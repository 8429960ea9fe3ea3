// The mesh readers of <raykernel/io/mesh_file.hpp>: hand-written files of every format and feature, with the
// expected vertices and triangles derived by hand in the comments; every kind of bad file with the position
// and reason its error must carry; round trips of the test meshes through every writer and reader, bit for
// bit.
#include <raykernel/io/mesh_file.hpp>
#include <raykernel/testkit/meshes.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

namespace raykernel::io {
namespace {

using Tri = std::array<std::uint32_t, 3>;

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }

void expect_mesh(const Mesh& m, const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles) {
  ASSERT_EQ(m.vertices.size(), vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    EXPECT_EQ(bits(m.vertices[i].x), bits(vertices[i].x)) << "vertex " << i << " x";
    EXPECT_EQ(bits(m.vertices[i].y), bits(vertices[i].y)) << "vertex " << i << " y";
    EXPECT_EQ(bits(m.vertices[i].z), bits(vertices[i].z)) << "vertex " << i << " z";
  }
  ASSERT_EQ(m.triangles.size(), triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) EXPECT_EQ(m.triangles[k], triangles[k]) << "triangle " << k;
}

// The error of reading `bytes`: its position and reason (the test fails if it reads).
mesh_file_error error_of(std::string_view bytes, MeshFormat format, std::string_view name = "test.file") {
  try {
    (void)read_mesh(bytes, name, format);
  } catch (const mesh_file_error& e) {
    return e;
  }
  ADD_FAILURE() << "read without an error:\n" << bytes.substr(0, 300);
  return mesh_file_error("", {}, "");
}

void expect_error(std::string_view bytes, MeshFormat format, FilePosition::Kind kind, std::uint64_t where,
                  std::string_view reason_part) {
  const mesh_file_error e = error_of(bytes, format);
  EXPECT_EQ(e.file(), "test.file");
  EXPECT_EQ(e.position().kind, kind) << e.what();
  EXPECT_EQ(e.position().value, where) << e.what();
  EXPECT_NE(e.reason().find(reason_part), std::string::npos) << e.what() << "\n  expected the reason to contain: " << reason_part;
}
void expect_line_error(std::string_view bytes, MeshFormat f, std::uint64_t line, std::string_view reason) {
  expect_error(bytes, f, FilePosition::Kind::line, line, reason);
}
void expect_byte_error(std::string_view bytes, MeshFormat f, std::uint64_t offset, std::string_view reason) {
  expect_error(bytes, f, FilePosition::Kind::byte_offset, offset, reason);
}

// ---- OBJ ----------------------------------------------------------------------------------------------

TEST(ObjReader, EveryFeature) {
  const std::string obj =
      "# a comment\r\n"
      "mtllib x.mtl\r\n"
      "o thing\n"
      "v 0 0 0 1\n"                  // vertex 1 (index 0), with w
      "v 1 0 0 0.5 0.5 0.5\n"        // vertex 2, with a colour
      "v 0x1p-1 1 0\n"               // vertex 3: x = 0.5
      "v 0.1 \\\n  0.2 0.3\n"        // vertex 4, continued over two lines
      "vt 0 1\nvn 0 0 1\ns off\ng group\nusemtl red\n"
      "f 1 2 3\n"                    // triangle (0, 1, 2)
      "f 1/1 2/1 3/1 4/1   # a quad: fanned into (0,1,2), (0,2,3)\n"
      "f -4//1 -3//1 -1//1\n"        // relative: 4 vertices so far → (0, 1, 3)
      "f 4/1/1 3/1/1 2/1/1 1/1/1 2/1/1\n"  // a pentagon: (3,2,1), (3,1,0), (3,0,1)
      "l 1 2\np 3\n";
  const Mesh m = read_mesh(obj, "t.obj", MeshFormat::obj);
  expect_mesh(m, {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.1, 0.2, 0.3}},
              {{0, 1, 2}, {0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {3, 2, 1}, {3, 1, 0}, {3, 0, 1}});
}

TEST(ObjReader, ForwardReferencesAndDecimalsExactly) {
  // Faces may come before the vertices they name. 0.1 must be the double nearest 1/10 (the literal 0.1 is
  // correctly rounded by the compiler); 1e-320 is subnormal, read exactly as strtod reads it.
  const Mesh m = read_mesh("f 1 2 3\nv 0.1 -0 1e-320\nv 2 2 2\nv 1.0000000000000002220446049250313080847263336181640625 3 3\n",
                           "t.obj", MeshFormat::obj);
  expect_mesh(m, {{0.1, -0.0, 1e-320}, {2, 2, 2}, {std::nextafter(1.0, 2.0), 3, 3}}, {{0, 1, 2}});
}

TEST(ObjReader, Errors) {
  using F = MeshFormat;
  expect_line_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", F::obj, 4, "vertex index 4 is out of range (the file has 3 vertices)");
  expect_line_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", F::obj, 4, "vertex index 0 is out of range");
  expect_line_error("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n", F::obj, 3, "relative vertex index -3 is out of range (2 vertices so far)");
  expect_line_error("v 0 0 0\nv 1 0 0\nf 1 2\n", F::obj, 3, "a face needs at least 3 vertices, this one has 2");
  expect_line_error("v 0 0 0\nv 1 nan 0\n", F::obj, 2, "y of vertex 2: 'nan' is not finite");
  expect_line_error("v 0 0 0\nv 1 0 inf\n", F::obj, 2, "z of vertex 2: 'inf' is not finite");
  expect_line_error("v 1e999 0 0\n", F::obj, 1, "x of vertex 1: '1e999' overflows the double range");
  expect_line_error("v 1e-400 0 0\n", F::obj, 1, "x of vertex 1: '1e-400' is nonzero but rounds to zero");
  expect_line_error("v 1 2\n", F::obj, 1, "z of vertex 1 is missing");
  expect_line_error("v 1 2 3x\n", F::obj, 1, "'3x' is not a number");
  expect_line_error("v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3/\n", F::obj, 4, "is not of the form");
  expect_line_error("v 1 2 3\nf 1 a 3\n", F::obj, 2, "'a' is not a vertex index");
  expect_line_error("# c\n\nvertex 1 2 3\n", F::obj, 3, "unknown statement 'vertex'");
  expect_line_error("v 0 0 0\r\nv 1 0 0\r\nv 0 \\\n 1 0\r\nf 1 2 5\r\n", F::obj, 5, "out of range");  // line numbers count continued lines
  expect_error("", F::obj, FilePosition::Kind::none, 0, "empty file");
  expect_error("  \n\t\n", F::obj, FilePosition::Kind::none, 0, "empty file");
  // Comments only: an empty mesh, not an error (an empty mesh written as OBJ is a comment line); found by
  // fuzz_mesh_reader (corpus: regression-obj-without-v-or-f).
  EXPECT_TRUE(read_mesh("# only\n# comments\n", "t.obj", F::obj).triangles.empty());
  EXPECT_TRUE(read_mesh("vp 0 1 0\n", "t.obj", F::obj).vertices.empty());
  expect_line_error("\x01\x02\x03 garbage\n", F::obj, 1, "unknown statement '\\x01\\x02\\x03'");
}

// Index extremes of every path of every reader (a regression: `f 1 2 -9223372036854775808` negated INT64_MIN, was
// taken as in range and loaded as vertex 3 when a fourth vertex followed, or aborted the CLI when none did).
TEST(ObjReader, IndexExtremesAreErrorsNeverWrappedIndices) {
  using F = MeshFormat;
  const std::string three = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_line_error(three + "f 1 2 -9223372036854775808\nv 0 0 1\n", F::obj, 4,
                    "relative vertex index -9223372036854775808 is out of range (3 vertices so far)");
  expect_line_error(three + "f 1 2 -9223372036854775808\n", F::obj, 4, "relative vertex index -9223372036854775808 is out of range");
  expect_line_error(three + "f 1 2 -9223372036854775807\n", F::obj, 4, "relative vertex index -9223372036854775807 is out of range");
  expect_line_error(three + "f 1 2 -9223372036854775809\n", F::obj, 4, "'-9223372036854775809' is not a vertex index");
  expect_line_error(three + "f 1 2 9223372036854775807\n", F::obj, 4, "vertex index 9223372036854775807 is out of range");
  expect_line_error(three + "f 1 2 9223372036854775808\n", F::obj, 4, "'9223372036854775808' is not a vertex index");
  expect_line_error(three + "f 1 2 4294967296\n", F::obj, 4, "vertex index 4294967296 is out of range");
  expect_line_error(three + "f 1 2 4294967297\n", F::obj, 4, "vertex index 4294967297 is out of range");
  expect_line_error(three + "f 1 2 -4294967296\n", F::obj, 4, "relative vertex index -4294967296 is out of range");
  // The relative index that reaches exactly the first vertex is fine; one more is not.
  expect_mesh(read_mesh(three + "f -3 -2 -1\n", "t.obj", F::obj), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{Tri{0, 1, 2}}});
  expect_line_error(three + "f -4 -2 -1\n", F::obj, 4, "relative vertex index -4 is out of range (3 vertices so far)");
}

TEST(OffReader, IndexExtremesAreErrors) {
  using F = MeshFormat;
  const std::string head = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  expect_line_error(head + "3 0 1 -9223372036854775808\n", F::off, 6, "vertex index -9223372036854775808 of face 0 is out of range");
  expect_line_error(head + "3 0 1 9223372036854775807\n", F::off, 6, "vertex index 9223372036854775807 of face 0 is out of range");
  expect_line_error(head + "3 0 1 4294967296\n", F::off, 6, "vertex index 4294967296 of face 0 is out of range");
  expect_line_error(head + "3 0 1 9223372036854775808\n", F::off, 6, "is not a vertex index");
  expect_line_error(head + "9223372036854775807 0 1 2\n", F::off, 6, "declares 9223372036854775807 vertices but lists 3");
  expect_line_error("OFF\n4294967296 0 0\n", F::off, 2, "expected the counts");
}

// ---- PLY ----------------------------------------------------------------------------------------------

template <class T>
void put(std::string& out, T value, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

TEST(PlyReader, AsciiWithExtraElementsAndProperties) {
  const std::string ply =
      "ply\r\nformat ascii 1.0\ncomment made by hand\nobj_info x\n"
      "element material 1\nproperty uchar red\nproperty list uchar float weights\n"
      "element vertex 4\nproperty float nx\nproperty double z\nproperty list uchar int ring\nproperty float y\n"
      "property float x\nproperty uchar alpha\n"
      "element face 2\nproperty uchar flags\nproperty list uchar int vertex_index\nproperty list int float uv\n"
      "end_header\n"
      "255 2 0.5 0.25\n"                // material: skipped (a list inside)
      "9 3 2 7 7 1 -0.5 0\n"            // vertex 0: z = 3, y = 1, x = -0.5 (nx = 9, ring [7, 7] skipped)
      "9 0.1 0 2 0 255\n"               // vertex 1: z = 0.1, y = 2, x = 0 (empty ring)
      "\n"                              // a blank line is skipped
      "9 0x1p-2 1 5 1e-300 1e300 0\n"   // vertex 2: z = 0.25, y = 1e-300, x = 1e300
      "9 -0 0 4 4 4\n"                  // vertex 3: z = -0, y = 4, x = 4
      "1 3 0 1 2 0\n"                   // face: (0, 1, 2), no uv
      "0 4 3 2 1 0 2 0.5 0.5\n";        // quad (3, 2, 1, 0) fanned: (3, 2, 1), (3, 1, 0)
  const Mesh m = read_mesh(ply, "t.ply", MeshFormat::ply);
  expect_mesh(m, {{-0.5, 1, 3}, {0, 2, 0.1}, {1e300, 1e-300, 0.25}, {4, 4, -0.0}}, {{0, 1, 2}, {3, 2, 1}, {3, 1, 0}});
}

std::string binary_ply(bool big, bool doubles) {
  std::string out = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\nelement vertex 3\nproperty short id\n" + (doubles ? "property double x\nproperty double y\nproperty double z\n"
                                                                             : "property float x\nproperty float y\nproperty float z\n") +
                    "property list uchar uchar extra\nelement face 1\nproperty list ushort uint vertex_indices\n"
                    "property int tag\nelement trailer 1\nproperty list int double junk\nend_header\n";
  const double coords[3][3] = {{0.1, 0.2, 0.3}, {1e-40, -2, 3}, {5, 6, 1e38}};
  for (int v = 0; v < 3; ++v) {
    put<std::int16_t>(out, static_cast<std::int16_t>(v), big);
    for (int a = 0; a < 3; ++a) {
      if (doubles) put<double>(out, coords[v][a], big);
      else put<float>(out, static_cast<float>(coords[v][a]), big);
    }
    put<std::uint8_t>(out, 2, big);
    put<std::uint8_t>(out, 9, big);
    put<std::uint8_t>(out, 9, big);
  }
  put<std::uint16_t>(out, 3, big);
  for (std::uint32_t i : {2u, 1u, 0u}) put<std::uint32_t>(out, i, big);
  put<std::int32_t>(out, -7, big);
  put<std::int32_t>(out, 2, big);
  put<double>(out, 1.5, big);
  put<double>(out, 2.5, big);
  return out;
}

TEST(PlyReader, BinaryBothEndiansFloatsWidenedExactly) {
  for (bool big : {false, true})
    for (bool doubles : {false, true}) {
      SCOPED_TRACE(std::string(big ? "big" : "little") + (doubles ? " double" : " float"));
      const Mesh m = read_mesh(binary_ply(big, doubles), "t.ply", MeshFormat::ply);
      // floats: each coordinate is the float nearest the decimal, widened exactly (double(float(0.1)) ≠ 0.1)
      auto c = [&](double x) { return doubles ? x : static_cast<double>(static_cast<float>(x)); };
      expect_mesh(m, {{c(0.1), c(0.2), c(0.3)}, {c(1e-40), -2, 3}, {5, 6, c(1e38)}}, {{2, 1, 0}});
    }
}

TEST(PlyReader, Errors) {
  using F = MeshFormat;
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                           "element face 1\nproperty list uchar int vertex_indices\nend_header\n";  // 9 header lines
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", F::ply, 13, "vertex index 3 of face 0 is out of range (3 vertices)");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", F::ply, 13, "vertex index -1 of face 0 is out of range");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", F::ply, 13, "face 0 has 2 vertices, a face needs at least 3");
  expect_line_error(head + "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", F::ply, 11, "y of vertex 1: 'nan' is not finite");
  expect_line_error(head + "0 0 0\n1 0 0\n", F::ply, 12, "truncated: the file ends before vertex 2");
  expect_line_error(head + "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n", F::ply, 11, "wrong counts");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", F::ply, 13, "wrong counts");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", F::ply, 14, "text follows the last element");
  expect_line_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", F::ply, 3,
                    "the vertex element has no property z");
  expect_line_error("ply\nformat ascii 2.0\nend_header\n", F::ply, 2, "unsupported PLY version");
  expect_line_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n", F::ply, 4, "unknown property type 'quad'");
  expect_line_error("ply\nformat ascii 1.0\nelement vertex 0\n", F::ply, 4, "no end_header");
  expect_line_error("ply\nformat ascii 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                    F::ply, 3, "wrong counts");
  expect_line_error("ply\nformat ascii 1.0\nelement face 1\nproperty list uchar float vertex_indices\nend_header\n3 0 1 2\n", F::ply, 3,
                    "must be a list of integers");
  expect_line_error("solid\n", F::ply, 1, "not a PLY file");
  // Index extremes of every integer type (ascii and binary): never wrapped into range.
  const std::string head_uint = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  expect_line_error(head_uint + "3 0 1 4294967295\n", F::ply, 13, "vertex index 4294967295 of face 0 is out of range");
  expect_line_error(head_uint + "3 0 1 4294967296\n", F::ply, 13, "is not an integer of its type");
  expect_line_error(head_uint + "3 0 1 -1\n", F::ply, 13, "is not an integer of its type");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2147483648\n", F::ply, 13, "vertex index -2147483648 of face 0 is out of range");
  expect_line_error(head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 -2147483649\n", F::ply, 13, "is not an integer of its type");
  // Binary: byte offsets.
  std::string b = binary_ply(false, false);
  const std::size_t body = b.find("end_header\n") + 11;
  // vertex k starts at body + k·17 (short id, 3 floats, list of 2 uchar: 2 + 12 + 3 bytes); its y at +6
  std::string nan_y = b;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan_y[body + 17 + 6], &nan, 4);
  expect_byte_error(nan_y, F::ply, body + 17 + 6, "y of vertex 1 is not finite");
  // the face's indices start at body + 3·17 + 2; the second is at + 4
  std::string bad_index = b;
  const std::uint32_t five = 5;
  std::memcpy(&bad_index[body + 51 + 2 + 4], &five, 4);
  expect_byte_error(bad_index, F::ply, body + 51 + 6, "vertex index 5 of face 0 is out of range (3 vertices)");
  for (const std::uint32_t extreme : {std::uint32_t{0x80000000}, std::uint32_t{0xffffffff}}) {  // the binary indices are uint
    std::string wrapped = b;
    std::memcpy(&wrapped[body + 51 + 2 + 4], &extreme, 4);
    expect_byte_error(wrapped, F::ply, body + 51 + 6, "vertex index " + std::to_string(extreme) + " of face 0 is out of range");
  }
  std::string two_vertices = b;
  two_vertices[body + 51] = 2;  // the face's count (ushort, little endian)
  expect_byte_error(two_vertices, F::ply, body + 51, "face 0 has 2 vertices");
  // Cut after the face's indices (body + 51 + 2 + 12): its int tag is missing. (A cut that leaves fewer bytes than
  // the header's counts need at the least is caught before any data is read: "wrong counts" at the element line.)
  expect_byte_error(b.substr(0, body + 65), F::ply, body + 65, "truncated: the file ends inside face 0");
  expect_line_error(b.substr(0, body + 40), F::ply, 3, "wrong counts: the header declares 3 vertex instances");
  expect_byte_error(b + "x", F::ply, b.size(), "1 bytes follow the last element");
  std::string long_list = b;
  long_list[body + 51] = '\xff';
  long_list[body + 52] = '\xff';  // 65535 indices: runs past the end
  expect_byte_error(long_list, F::ply, body + 51, "runs past the end of the file");
}

// ---- STL ----------------------------------------------------------------------------------------------

std::string binary_stl(const std::vector<std::array<float, 9>>& facets, std::string header) {
  header.resize(80, ' ');
  std::string out = header;
  put<std::uint32_t>(out, static_cast<std::uint32_t>(facets.size()), false);
  for (const auto& f : facets) {
    for (int i = 0; i < 3; ++i) put<float>(out, 0.0f, false);
    for (float c : f) put<float>(out, c, false);
    put<std::uint16_t>(out, 0, false);
  }
  return out;
}

TEST(StlReader, BinaryEvenWithASolidHeaderNothingWelded) {
  // Two facets sharing an edge: 6 vertices, nothing welded.
  const std::string stl = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}, {1, 0, 0, 0.1f, 1, 0, 0, 1, 0}}, "solid but binary");
  const Mesh m = read_mesh(stl, "t.stl", MeshFormat::stl);
  expect_mesh(m, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {static_cast<double>(0.1f), 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(sniff_format(stl), MeshFormat::stl);
}

TEST(StlReader, Ascii) {
  const std::string stl =
      "solid two parts\n"
      "  facet normal 0 0 1\n    outer loop\n      vertex 0 0 0\n      vertex 1 0 0\n      vertex 0 1 0\n    endloop\n  endfacet\n"
      "endsolid two parts\r\n"
      "solid second\n facet normal nan 0 0\n outer loop\n vertex 0.1 0 0\n vertex 1 0 0\n vertex 1 1 0\n vertex 0 1 0\n"
      " endloop\n endfacet\nendsolid\n";
  // The second facet is a quad, fanned: (3, 4, 5), (3, 5, 6). A NaN normal is ignored.
  const Mesh m = read_mesh(stl, "t.stl", MeshFormat::stl);
  expect_mesh(m, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {3, 4, 5}, {3, 5, 6}});
}

TEST(StlReader, Errors) {
  using F = MeshFormat;
  const std::string ok = binary_stl({{0, 0, 0, 1, 0, 0, 0, 1, 0}}, "x");
  std::string inf = ok;
  const float infinity = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[84 + 12 + 12 + 4], &infinity, 4);  // y of vertex 1 of facet 0
  expect_byte_error(inf, F::stl, 84 + 28, "y of vertex 1 of facet 0 is not finite");
  expect_byte_error(ok.substr(0, 120), F::stl, 120, "truncated: the header declares 1 facets (134 bytes)");
  expect_byte_error(ok + "zz", F::stl, 134, "wrong counts");
  expect_byte_error(std::string(50, 'x'), F::stl, 50, "truncated: a binary STL file has at least 84 bytes");
  expect_line_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n", F::stl, 6,
                    "facet 0 has 2 vertices");
  expect_line_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1e-999 0\nendloop\nendfacet\nendsolid\n",
                    F::stl, 6, "y of a vertex of facet 0: '1e-999' is nonzero but rounds to zero");
  expect_line_error("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n", F::stl, 4, "expected 'vertex' or 'endloop', found the end of the file");
  expect_line_error("solid x\nfacet 0 0 1\n", F::stl, 2, "expected 'normal' after 'facet', found '0'");
  expect_line_error("solid x\nendsolid x\nhello\n", F::stl, 3, "expected 'solid', found 'hello'");
}

// ---- OFF ----------------------------------------------------------------------------------------------

TEST(OffReader, CommentsColoursAndPolygons) {
  const std::string off =
      "# header comment\nCOFF 5 2 0\n"
      "0 0 0 255 0 0 255\n"          // vertex 0 with a colour
      "1 0 0\n\n# between\n"
      "1 1 0 # trailing comment\n"
      "0 1 0\n"
      "0x1p-1 0.5 1\n"               // vertex 4 = (0.5, 0.5, 1)
      "4 0 1 2 3 0.5 0.5 0.5 1\n"    // quad with a colour: (0, 1, 2), (0, 2, 3)
      "3 4 3 2\n";                    // (4, 3, 2)
  const Mesh m = read_mesh(off, "t.off", MeshFormat::off);
  expect_mesh(m, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 1}}, {{0, 1, 2}, {0, 2, 3}, {4, 3, 2}});
  // Counts on their own line, and no edge count.
  expect_mesh(read_mesh("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "t.off", MeshFormat::off), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
}

TEST(OffReader, Errors) {
  using F = MeshFormat;
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", F::off, 6, "vertex index 3 of face 0 is out of range (3 vertices)");
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", F::off, 6, "face 0 has 2 vertices");
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", F::off, 6, "wrong counts: face 0 declares 4 vertices but lists 3");
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 0 0\n# padding padding padding\n", F::off, 6, "truncated: the file ends before vertex 2");
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n", F::off, 4, "y of vertex 1: 'inf' is not finite");
  expect_line_error("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", F::off, 7, "follows the last face");
  expect_line_error("4OFF\n", F::off, 1, "other dimensions");
  expect_line_error("OFF BINARY\n", F::off, 1, "binary OFF files are not supported");
  expect_line_error("OFF\n99999999 1 0\n0 0 0\n", F::off, 2, "wrong counts");
  expect_line_error("MESH\n", F::off, 1, "expected the OFF keyword");
}

// ---- Files, formats, round trips ----------------------------------------------------------------------

TEST(MeshFiles, FormatFromExtensionAndContent) {
  EXPECT_EQ(format_from_extension("a/b.OBJ"), MeshFormat::obj);
  EXPECT_EQ(format_from_extension("x.Ply"), MeshFormat::ply);
  EXPECT_EQ(format_from_extension("x.stl"), MeshFormat::stl);
  EXPECT_EQ(format_from_extension("x.off"), MeshFormat::off);
  EXPECT_FALSE(format_from_extension("x.mesh").has_value());
  EXPECT_EQ(sniff_format("ply\nformat ascii 1.0\n"), MeshFormat::ply);
  EXPECT_EQ(sniff_format("# c\nOFF\n"), MeshFormat::obj);  // a comment first: OBJ's convention (OFF files start with OFF)
  EXPECT_EQ(sniff_format("COFF\n3 1 0\n"), MeshFormat::off);
  EXPECT_EQ(sniff_format("solid x\n"), MeshFormat::stl);
  EXPECT_EQ(sniff_format("v 1 2 3\n"), MeshFormat::obj);
  EXPECT_FALSE(sniff_format("hello world").has_value());
  EXPECT_FALSE(sniff_format("OFFICE").has_value());
}

TEST(MeshFiles, ReadFromDiskNamesTheFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("raykernel-io-test-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  };
  expect_mesh(read_mesh(write("a.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  expect_mesh(read_mesh(write("noext", "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  try {
    (void)read_mesh(write("bad.obj", "v 0 0 0\nf 1 1 9\n"));
    ADD_FAILURE() << "no error";
  } catch (const mesh_file_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "bad.obj").string() + ":2: vertex index 9 is out of range (the file has 1 vertex)");
  }
  for (const auto& [name, reason] : std::vector<std::pair<std::string, std::string>>{
           {"missing.obj", "cannot open: No such file or directory"}, {"empty.ply", "empty file"}, {"junk", "unknown format"}}) {
    if (name != "missing.obj") write(name, name == "junk" ? "hello\n" : "");
    try {
      (void)read_mesh(dir / name);
      ADD_FAILURE() << name << ": no error";
    } catch (const mesh_file_error& e) {
      EXPECT_EQ(e.file(), (dir / name).string());
      EXPECT_EQ(e.position().kind, FilePosition::Kind::none);
      EXPECT_NE(e.reason().find(reason), std::string::npos) << e.what();
    }
  }
  try {  // a device is refused before it is read (reading /dev/zero would never end)
    (void)read_mesh("/dev/zero");
    ADD_FAILURE() << "/dev/zero: no error";
  } catch (const mesh_file_error& e) {
    EXPECT_EQ(e.file(), "/dev/zero");
    EXPECT_NE(e.reason().find("device"), std::string::npos) << e.what();
  }
  // Regression: a NUL in the name ended it for the system's calls, and "a.obj\0x" read a.obj. Refused.
  try {
    (void)read_mesh(std::filesystem::path((dir / "a.obj").string() + std::string("\0x", 2)));
    ADD_FAILURE() << "a name with a NUL: no error";
  } catch (const mesh_file_error& e) {
    EXPECT_EQ(e.position().kind, FilePosition::Kind::none);
    EXPECT_EQ(e.reason(), "the file name contains a NUL character, which no file name can hold");
  }
  std::filesystem::remove_all(dir);
}

TEST(MeshFiles, RoundTripsBitForBit) {
  Mesh odd = testkit::make_icosphere(2);  // vertices on a 2^-30 grid; add awkward doubles too
  odd.vertices.push_back({0.1, -0.0, std::numeric_limits<double>::denorm_min()});
  odd.vertices.push_back({-1e308, 1e-310, 3.0000000000000004});
  odd.triangles.push_back({0, static_cast<std::uint32_t>(odd.vertices.size() - 2), static_cast<std::uint32_t>(odd.vertices.size() - 1)});
  const Mesh meshes[] = {testkit::make_octahedron(), testkit::make_subdivided_cube(3), testkit::make_terrain(4), odd};
  for (const Mesh& m : meshes) {
    for (auto [format, encoding] : {std::pair{MeshFormat::obj, MeshEncoding::ascii}, {MeshFormat::off, MeshEncoding::ascii},
                                    {MeshFormat::ply, MeshEncoding::ascii}, {MeshFormat::ply, MeshEncoding::binary_little_endian},
                                    {MeshFormat::ply, MeshEncoding::binary_big_endian}}) {
      SCOPED_TRACE(std::string(to_string(format)) + " " + std::to_string(static_cast<int>(encoding)));
      expect_mesh(read_mesh(write_mesh(m, format, encoding), "rt", format), m.vertices, m.triangles);
    }
    // STL unshares the vertices: triangle k becomes (3k, 3k+1, 3k+2) with the same coordinates.
    Mesh unshared;
    for (std::size_t k = 0; k < m.triangles.size(); ++k) {
      const Triangle t = m.triangle(k);
      for (const Vec3& v : {t.a, t.b, t.c}) unshared.vertices.push_back(v);
      const auto f = static_cast<std::uint32_t>(3 * k);
      unshared.triangles.push_back({f, f + 1, f + 2});
    }
    expect_mesh(read_mesh(write_mesh(m, MeshFormat::stl), "rt", MeshFormat::stl), unshared.vertices, unshared.triangles);
  }
  // Binary STL: floats only.
  const Mesh octa = testkit::make_octahedron(0.5);
  const Mesh back = read_mesh(write_mesh(octa, MeshFormat::stl, MeshEncoding::binary_little_endian), "rt", MeshFormat::stl);
  EXPECT_EQ(back.triangles.size(), octa.triangles.size());
  EXPECT_THROW((void)write_mesh(odd, MeshFormat::stl, MeshEncoding::binary_little_endian), std::invalid_argument);
}

TEST(MeshValidate, NamesTheFirstProblem) {
  Mesh m = testkit::make_octahedron();
  EXPECT_FALSE(validate(m).has_value());
  m.triangles[3][1] = 6;
  EXPECT_EQ(validate(m), std::optional<std::string>("triangle 3: vertex index 6 is out of range (6 vertices)"));
  m.vertices[2].y = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validate(m), std::optional<std::string>("vertex 2: y is not finite"));
}

}  // namespace
}  // namespace raykernel::io
