// glTF 2.0 meshes (io/src/read_gltf.cpp): hand-built .gltf and .glb files (a buffer of float32 positions and
// integer indices, written here byte by byte) with their vertices and triangles derived by hand — float32 values
// widened exactly, the specification's strip and fan orders, exact node transforms — and every kind of bad file
// with the reason its error must give.
#include <raykernel/io/mesh_file.hpp>

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace raykernel::io {
namespace {

using Tri = std::array<std::uint32_t, 3>;

#if RAYKERNEL_TEST_GLTF

std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16 | static_cast<std::uint8_t>(bytes[i + 1]) << 8 |
                            static_cast<std::uint8_t>(bytes[i + 2]);
    for (int k = 18; k >= 0; k -= 6) out += digits[(v >> k) & 63];
  }
  if (i + 1 == bytes.size()) {
    const std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16;
    out += digits[(v >> 18) & 63], out += digits[(v >> 12) & 63], out += "==";
  } else if (i + 2 == bytes.size()) {
    const std::uint32_t v = static_cast<std::uint8_t>(bytes[i]) << 16 | static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    out += digits[(v >> 18) & 63], out += digits[(v >> 12) & 63], out += digits[(v >> 6) & 63], out += '=';
  }
  return out;
}

template <class T>
void append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // little-endian host, as glTF
  bytes.append(raw, sizeof(T));
}

// The buffer of the test files: 4 float32 positions (48 bytes) then 6 uint16 indices (12 bytes).
const std::array<std::array<float, 3>, 4> positions{{{0.1f, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1e-40f}}};  // 1e-40f: subnormal
std::string test_buffer(const std::vector<std::uint16_t>& indices = {0, 1, 2, 0, 2, 3}) {
  std::string b;
  for (const auto& p : positions)
    for (const float c : p) append(b, c);
  for (const std::uint16_t i : indices) append(b, i);
  return b;
}

// A glTF JSON document around `buffer` (as a data: URI unless `uri` is given); `primitive`, `nodes` and `scenes`
// are spliced in as JSON.
std::string gltf(const std::string& buffer, const std::string& primitive, const std::string& nodes = "",
                 const std::string& extra = "", const std::string& uri = "") {
  const std::string u = uri.empty() ? "data:application/octet-stream;base64," + base64(buffer) : uri;
  return R"({"asset": {"version": "2.0"},
  "buffers": [{"byteLength": )" + std::to_string(buffer.size()) + R"(, "uri": ")" + u + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": )" + std::to_string(buffer.size() - 48) + R"(}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
                {"bufferView": 1, "componentType": 5123, "count": )" + std::to_string((buffer.size() - 48) / 2) +
         R"(, "type": "SCALAR"}],
  "meshes": [{"primitives": [)" + primitive + R"(]}])" + nodes + extra + "}";
}

const std::string triangles_primitive = R"({"attributes": {"POSITION": 0}, "indices": 1})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

std::vector<Vec3> widened() {
  std::vector<Vec3> v;
  for (const auto& p : positions) v.push_back({p[0], p[1], p[2]});
  return v;
}

void expect_mesh(const Mesh& m, const std::vector<Vec3>& vertices, const std::vector<Tri>& triangles) {
  ASSERT_EQ(m.vertices.size(), vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.vertices[i].x), std::bit_cast<std::uint64_t>(vertices[i].x)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.vertices[i].y), std::bit_cast<std::uint64_t>(vertices[i].y)) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(m.vertices[i].z), std::bit_cast<std::uint64_t>(vertices[i].z)) << i;
  }
  ASSERT_EQ(m.triangles.size(), triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) EXPECT_EQ(m.triangles[k], triangles[k]) << "triangle " << k;
}

// The error's reason when reading `text` as glTF from memory.
std::string error_of(const std::string& text) {
  try {
    (void)read_mesh(text, "t.gltf", MeshFormat::gltf);
  } catch (const mesh_file_error& e) {
    EXPECT_EQ(e.file(), "t.gltf");
    return e.reason();
  }
  return "(no error)";
}

TEST(Gltf, TrianglesAreReadExactlyFromJsonWithADataUri) {
  const std::string text = gltf(test_buffer(), triangles_primitive);
  EXPECT_EQ(sniff_format(text), MeshFormat::gltf);
  EXPECT_EQ(format_from_extension("a/B.GLTF"), MeshFormat::gltf);
  EXPECT_EQ(format_from_extension("b.glb"), MeshFormat::gltf);
  // 0.1f is 13421773·2^-27 = 0.100000001490116119384765625, 1e-40f the subnormal 71362·2^-149: widened exactly.
  const Mesh m = read_mesh(text, "t.gltf", MeshFormat::gltf);
  EXPECT_EQ(m.vertices[0].x, 13421773 * 0x1p-27);
  EXPECT_EQ(m.vertices[3].z, 71362 * 0x1p-149);
  expect_mesh(m, widened(), {{0, 1, 2}, {0, 2, 3}});
}

TEST(Gltf, TheSameMeshFromABinaryGlb) {
  // GLB: 12-byte header, a JSON chunk (padded with spaces to 4 bytes), a BIN chunk (the buffer without a uri).
  std::string json = gltf(test_buffer(), triangles_primitive);
  const std::string uri = R"(, "uri": "data:application/octet-stream;base64,)" + base64(test_buffer()) + "\"";
  json.erase(json.find(uri), uri.size());
  while (json.size() % 4) json += ' ';
  const std::string bin = test_buffer();
  std::string glb = "glTF";
  append<std::uint32_t>(glb, 2);
  append<std::uint32_t>(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  append<std::uint32_t>(glb, static_cast<std::uint32_t>(json.size()));
  glb += "JSON" + json;
  append<std::uint32_t>(glb, static_cast<std::uint32_t>(bin.size()));
  glb += std::string("BIN\0", 4) + bin;
  EXPECT_EQ(sniff_format(glb), MeshFormat::gltf);
  expect_mesh(read_mesh(glb, "t.glb", MeshFormat::gltf), widened(), {{0, 1, 2}, {0, 2, 3}});
}

TEST(Gltf, StripsFansUnindexedPrimitivesAndSkippedLines) {
  // Strip over indices 0 1 2 3 (modes 5): p_0 = (v0, v1, v2), p_1 = (v1, v3, v2) (i odd: v_i, v_{i+2}, v_{i+1}).
  const std::string indices = R"("indices": 1)";
  const std::string strip = R"({"attributes": {"POSITION": 0}, "mode": 5, )" + indices + "}";
  const std::string buffer = test_buffer({0, 1, 2, 3});
  expect_mesh(read_mesh(gltf(buffer, strip), "t", MeshFormat::gltf), widened(), {{0, 1, 2}, {1, 3, 2}});
  // Fan (mode 6): p_i = (v_{i+1}, v_{i+2}, v_0).
  const std::string fan = R"({"attributes": {"POSITION": 0}, "mode": 6, )" + indices + "}";
  expect_mesh(read_mesh(gltf(buffer, fan), "t", MeshFormat::gltf), widened(), {{1, 2, 0}, {2, 3, 0}});
  // No indices: the vertices in order, 4 of them → one triangle and a leftover vertex is an error (4 % 3 ≠ 0);
  // lines (mode 1) are skipped; each primitive brings its own vertices.
  const std::string lines = R"({"attributes": {"POSITION": 0}, "mode": 1})";
  const std::string unindexed = R"({"attributes": {"POSITION": 0}})";
  EXPECT_NE(error_of(gltf(buffer, unindexed)).find("4 indices is not a multiple of 3"), std::string::npos);
  const Mesh two = read_mesh(gltf(buffer, lines + ", " + strip + ", " + fan), "t", MeshFormat::gltf);
  std::vector<Vec3> twice = widened();
  for (const Vec3& v : widened()) twice.push_back(v);
  expect_mesh(two, twice, {{0, 1, 2}, {1, 3, 2}, {5, 6, 4}, {6, 7, 4}});
}

TEST(Gltf, ExactNodeTransformsAreAppliedInnermostFirst) {
  // Node 0 (root): translation (1, 0, 0); node 1 (its child, with the mesh): scale (2, 4, 0.5). Vertex 0
  // (0.1f, 0, 0) → (2·0.1f, 0, 0) → (1 + 2·0.1f, 0, 0): (2^26 + 13421773)·2^-26 needs 27 bits, exact; vertex 3's
  // z, 71362·2^-149, halves exactly (a double, not a float32 subnormal).
  const std::string nodes = R"(, "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"translation": [1, 0, 0], "children": [1]}, {"mesh": 0, "scale": [2, 4, 0.5]}])";
  const Mesh m = read_mesh(gltf(test_buffer(), triangles_primitive, nodes), "t", MeshFormat::gltf);
  const double tenth = 13421773 * 0x1p-27;
  expect_mesh(m, {{1 + 2 * tenth, 0, 0}, {3, 0, 0}, {1, 4, 0}, {1, 0, 71362 * 0x1p-150}}, {{0, 1, 2}, {0, 2, 3}});
  // A translation that would add 0.5 to that z is refused: 0.5 + 35681·2^-149 needs 149 bits.
  EXPECT_NE(error_of(gltf(test_buffer(), triangles_primitive, R"(, "scenes": [{"nodes": [0]}],
    "nodes": [{"mesh": 0, "scale": [2, 4, 0.5], "translation": [0, 0, 0.5]}])")).find("POSITION 3"), std::string::npos);
  // The same as a matrix (column-major, translation in m[12..14]).
  const std::string matrix = R"(, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0,
    "matrix": [2, 0, 0, 0,  0, 4, 0, 0,  0, 0, 0.5, 0,  1, 0, 0, 1]}])";
  expect_mesh(read_mesh(gltf(test_buffer(), triangles_primitive, matrix), "t", MeshFormat::gltf), m.vertices,
              {{0, 1, 2}, {0, 2, 3}});
  // A file without scenes: every mesh as stored, transforms or not.
  expect_mesh(read_mesh(gltf(test_buffer(), triangles_primitive, R"(, "nodes": [{"mesh": 0, "scale": [3, 3, 3]}])"),
                        "t", MeshFormat::gltf),
              widened(), {{0, 1, 2}, {0, 2, 3}});
}

TEST(Gltf, InexactTransformsRotationsAndBrokenNodeGraphsAreRefused) {
  const auto with_nodes = [&](const std::string& nodes) {
    return error_of(gltf(test_buffer(), triangles_primitive, R"(, "scenes": [{"nodes": [0]}], "nodes": )" + nodes));
  };
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476]}])").find("node 0: it rotates"),
            std::string::npos);
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "matrix": [1,0,0,0, 1,1,0,0, 0,0,1,0, 0,0,0,1]}])").find("shears"), std::string::npos);
  // 0.1f + 2^-60 is not a double: 0.1f's last bit is 2^-27·… the sum needs 57 bits.
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "translation": [8.673617379884035e-19, 0, 0]}])").find("is not exact"),
            std::string::npos);
  // 0.1f·3 needs 26 bits: exact; 0.1f·0.1 is not.
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "scale": [0.1, 1, 1]}])").find("node 0: its transform of POSITION 0"),
            std::string::npos);
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "children": [1]}, {"children": [0]}])").find("not a forest"), std::string::npos);
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "children": [0]}])").find("not a forest"), std::string::npos);
  EXPECT_NE(with_nodes(R"([{"mesh": 0, "children": [5]}])").find("node 5 does not exist"), std::string::npos);
  EXPECT_NE(with_nodes(R"([{"mesh": 3}])").find("mesh 3 does not exist"), std::string::npos);
}

TEST(Gltf, BadAccessorsIndicesAndCoordinatesAreNamed) {
  EXPECT_NE(error_of(gltf(test_buffer({0, 1, 4, 0, 2, 3}), triangles_primitive)).find("index 2 is 4, out of range (4 vertices)"),
            std::string::npos);
  std::string buffer = test_buffer();
  const float infinity = std::numeric_limits<float>::infinity();
  std::memcpy(buffer.data() + 12 + 4, &infinity, 4);  // vertex 1's y
  EXPECT_NE(error_of(gltf(buffer, triangles_primitive)).find("POSITION 1: y is not finite"), std::string::npos);
  // An accessor claiming more elements than its view holds, and a view outside its buffer.
  std::string text = gltf(test_buffer(), triangles_primitive);
  const std::string more = replaced(text, R"("count": 4)", R"("count": 5)");
  EXPECT_NE(error_of(more).find("5 elements from byte 0 run past its buffer view (48 bytes)"), std::string::npos);
  const std::string outside = replaced(text, R"("byteLength": 48)", R"("byteLength": 4800)");
  EXPECT_NE(error_of(outside).find("lies outside its buffer"), std::string::npos);
  const std::string sparse = replaced(text, R"("type": "VEC3"})",
                 R"("type": "VEC3", "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 0}}})");
  EXPECT_NE(error_of(sparse).find("sparse accessors are not supported"), std::string::npos);
  const std::string quantized = replaced(text, R"("componentType": 5126)", R"("componentType": 5123)");
  EXPECT_NE(error_of(quantized).find("POSITION must be float32"), std::string::npos);
  EXPECT_NE(error_of(gltf(test_buffer(), R"({"attributes": {"NORMAL": 0}})")).find("no POSITION attribute"),
            std::string::npos);
  EXPECT_NE(error_of("{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [").find("not a valid glTF 2.0 JSON file"),
            std::string::npos);
  EXPECT_NE(error_of(std::string("glTF\x02\0\0\0\x10\0\0\0", 12)).find("not a valid glTF 2.0 binary (GLB) file"), std::string::npos);
  // No buffer view: zeros, but not more of them than the file has bytes.
  const std::string zeros = replaced(text, R"({"bufferView": 0, "componentType": 5126, "count": 4)",
                                     R"({"componentType": 5126, "count": 4000000000)");
  EXPECT_NE(error_of(zeros).find("without a buffer view (zeros), more than the file has bytes"), std::string::npos);
}

TEST(Gltf, ExternalBuffersAreReadBesideTheFileAndNeverFromMemory) {
  const std::string text = gltf(test_buffer(), triangles_primitive, "", "", "tetra.bin");
  EXPECT_NE(error_of(text).find("external file"), std::string::npos);
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / ("raykernel-gltf-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "tetra.gltf", std::ios::binary) << text;
  std::ofstream(folder / "tetra.bin", std::ios::binary) << test_buffer();
  expect_mesh(read_mesh(folder / "tetra.gltf"), widened(), {{0, 1, 2}, {0, 2, 3}});
  std::filesystem::remove(folder / "tetra.bin");
  try {
    (void)read_mesh(folder / "tetra.gltf");
    ADD_FAILURE() << "a missing external buffer was not refused";
  } catch (const mesh_file_error& e) {
    EXPECT_NE(std::string(e.what()).find("tetra.gltf"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(folder);
  EXPECT_THROW((void)write_mesh(read_mesh(gltf(test_buffer(), triangles_primitive), "t", MeshFormat::gltf),
                                MeshFormat::gltf),
               std::invalid_argument);
}

#else

TEST(Gltf, WithoutTinygltfAGltfFileIsRefusedWithTheReason) {
  try {
    (void)read_mesh("{\"asset\": {}}", "t.gltf", MeshFormat::gltf);
    ADD_FAILURE() << "no error";
  } catch (const mesh_file_error& e) {
    EXPECT_NE(e.reason().find("glTF support is not built in"), std::string::npos);
  }
}

#endif

}  // namespace
}  // namespace raykernel::io
