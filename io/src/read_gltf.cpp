// glTF 2.0 meshes (.gltf, .glb), read exactly with tinygltf (Debian's libtinygltf-dev; README.md, "Mesh files").
//
// tinygltf parses the JSON (nlohmann-json: numbers through strtod, correctly rounded), the GLB container and the
// buffers (data: URIs, the GLB binary chunk, and external files next to a .gltf); raykernel then reads the
// accessors itself, checking every index, offset, stride and length against the bytes there are:
//   - Vertices: each triangle primitive's POSITION accessor, float32 VEC3, widened to double exactly; NaN or
//     infinite coordinates are refused. Sparse, normalized and quantized (KHR_mesh_quantization) positions are
//     refused. An accessor without a buffer view is zeros, as the specification says.
//   - Triangles: modes TRIANGLES (4; the default), TRIANGLE_STRIP (5) and TRIANGLE_FAN (6), their vertices in
//     the order the specification gives (strip: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2−i%2)}}; fan: p_i = {v_{i+1},
//     v_{i+2}, v_0}); indices as stored (unsigned byte, short or int), each checked against the primitive's
//     vertex count; without indices, the vertices in order. Points and lines (modes 0–3) are not surfaces: skipped.
//     Every primitive's vertices are its own (appended in order; nothing welded).
//   - Nodes: the default scene's (or the first scene's) node trees, depth first in file order, each mesh placed
//     by the transforms from its node to the root — applied only when exact: a translation and a per-axis scale
//     (a matrix of that form, or TRS without rotation) whose every product and sum is exact for every vertex
//     (checked vertex by vertex: io::exact_affine, <raykernel/io/transform.hpp>). A rotation, a shear, a projective matrix or an
//     inexact result is refused, naming the node: a rotated vertex is irrational or needs more bits than a
//     double, and a rounded one would not be the file's mesh. A file without scenes gives every mesh as stored.
//     A node graph that is not a forest (a cycle, two parents) is refused.
//   - External files (a .gltf's .bin buffers) are read when the file is read from a path, relative to its
//     folder, regular files only; from memory (read_mesh(bytes, …)) they are refused. Images are never decoded.
// Everything else (materials, normals, skins, morph targets, animations, cameras) is ignored.
#include "reader_support.hpp"

#include <raykernel/fp_environment.hpp>
#include <raykernel/io/transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#if RAYKERNEL_WITH_TINYGLTF
#include <tiny_gltf.h>
#endif

namespace raykernel::io::detail {

#if !RAYKERNEL_WITH_TINYGLTF

Mesh read_gltf(std::string_view, const ErrorSink& errors, const std::filesystem::path*) {
  errors.whole_file("glTF support is not built in (tiny_gltf.h, Debian's libtinygltf-dev, was not found when "
                    "raykernel was configured)");
}

#else

namespace {

static_assert(std::numeric_limits<float>::is_iec559 && sizeof(float) == 4, "glTF floats are IEEE binary32");

// The folder external buffers are read from, or none (reading from memory: external files are refused).
struct FileAccess {
  const std::filesystem::path* folder;
};

bool ignore_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                  void*) {
  return true;  // images are not geometry: never decoded
}

bool file_exists(const std::string& path, void* user) {
  // From memory: "exists", so that read_whole_file is asked and says why it is not read.
  if (static_cast<const FileAccess*>(user)->folder == nullptr) return true;
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string expand_file_path(const std::string& path, void*) { return path; }  // no ~ or $VARIABLE expansion

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  if (static_cast<const FileAccess*>(user)->folder == nullptr) {
    *err = "external file '" + path + "': not read when the glTF is read from memory (only data: URIs)";
    return false;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    *err = "external file '" + path + "': not found or not a regular file";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) {
    *err = "external file '" + path + "': cannot be read";
    return false;
  }
  return true;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  *err = "raykernel does not write glTF files";
  return false;
}

// An accessor's elements: `count` elements of `size` bytes, `stride` apart from `data` (nullptr: all zeros).
struct Elements {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0, size = 0;
  int component_type = 0;
};

std::size_t component_bytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return 8;
    default: return 0;
  }
}

// a + b, or false when it overflows 64 bits.
bool add(std::uint64_t a, std::uint64_t b, std::uint64_t& sum) { return !__builtin_add_overflow(a, b, &sum); }
bool multiply(std::uint64_t a, std::uint64_t b, std::uint64_t& product) {
  return !__builtin_mul_overflow(a, b, &product);
}

class Reader {
 public:
  Reader(const tinygltf::Model& model, const ErrorSink& errors, std::size_t file_size)
      : model_(model), errors_(errors), file_size_(file_size) {}

  Mesh read() {
    if (model_.scenes.empty()) {
      for (std::size_t m = 0; m < model_.meshes.size(); ++m) add_mesh(m, {});
      return std::move(mesh_);
    }
    check_forest();
    const std::size_t scene =
        model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) < model_.scenes.size()
            ? static_cast<std::size_t>(model_.defaultScene)
            : 0;
    if (model_.defaultScene >= 0 && static_cast<std::size_t>(model_.defaultScene) >= model_.scenes.size())
      errors_.whole_file("the default scene " + std::to_string(model_.defaultScene) + " does not exist (" +
                         count_of(model_.scenes.size(), "scene", "scenes") + ")");
    std::vector<std::size_t> path;
    for (const int root : model_.scenes[scene].nodes) visit(node_index(root, "scene " + std::to_string(scene)), path);
    return std::move(mesh_);
  }

 private:
  // An affine map x ↦ scale·x + translation, per axis.
  struct Placement {
    std::array<double, 3> scale{1, 1, 1}, translation{0, 0, 0};
  };

  std::size_t node_index(int index, const std::string& where) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      errors_.whole_file(where + ": node " + std::to_string(index) + " does not exist (" +
                         count_of(model_.nodes.size(), "node", "nodes") + ")");
    return static_cast<std::size_t>(index);
  }

  // Every node has at most one parent, and no node is its own ancestor.
  void check_forest() const {
    std::vector<int> parent(model_.nodes.size(), -1);
    for (std::size_t n = 0; n < model_.nodes.size(); ++n)
      for (const int child : model_.nodes[n].children) {
        const std::size_t c = node_index(child, "node " + std::to_string(n));
        if (parent[c] >= 0 || c == n)
          errors_.whole_file("node " + std::to_string(c) + " has two parents or is its own child: the nodes are not "
                             "a forest");
        parent[c] = static_cast<int>(n);
      }
    for (std::size_t n = 0; n < model_.nodes.size(); ++n) {  // a cycle: walking up never ends at a root
      std::size_t steps = 0;
      for (int p = parent[n]; p >= 0; p = parent[static_cast<std::size_t>(p)])
        if (++steps > model_.nodes.size())
          errors_.whole_file("node " + std::to_string(n) + " is its own ancestor: the nodes are not a forest");
    }
  }

  Placement placement_of(std::size_t n) const {
    const tinygltf::Node& node = model_.nodes[n];
    const std::string where = "node " + std::to_string(n);
    Placement p;
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) errors_.whole_file(where + ": a matrix needs 16 numbers");
      const std::vector<double>& m = node.matrix;  // column-major
      for (const int k : {1, 2, 3, 4, 6, 7, 8, 9, 11})
        if (m[static_cast<std::size_t>(k)] != 0)
          errors_.whole_file(where + ": its matrix rotates, shears or projects; raykernel applies only exact "
                             "transforms (translations and per-axis scalings)");
      if (m[15] != 1) errors_.whole_file(where + ": its matrix is projective (m[3][3] is not 1)");
      p.scale = {m[0], m[5], m[10]};
      p.translation = {m[12], m[13], m[14]};
    } else {
      if (!node.rotation.empty()) {
        if (node.rotation.size() != 4) errors_.whole_file(where + ": a rotation needs 4 numbers");
        if (node.rotation[0] != 0 || node.rotation[1] != 0 || node.rotation[2] != 0 || node.rotation[3] != 1)
          errors_.whole_file(where + ": it rotates; raykernel applies only exact transforms (translations and "
                             "per-axis scalings): a rotated vertex is not a double in general");
      }
      if (!node.scale.empty()) {
        if (node.scale.size() != 3) errors_.whole_file(where + ": a scale needs 3 numbers");
        p.scale = {node.scale[0], node.scale[1], node.scale[2]};
      }
      if (!node.translation.empty()) {
        if (node.translation.size() != 3) errors_.whole_file(where + ": a translation needs 3 numbers");
        p.translation = {node.translation[0], node.translation[1], node.translation[2]};
      }
    }
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(p.scale[static_cast<std::size_t>(i)]) ||
          !std::isfinite(p.translation[static_cast<std::size_t>(i)]))
        errors_.whole_file(where + ": its transform is not finite");
    return p;
  }

  // Depth first from `root`, children in file order; `path` is the nodes from a root to the current one.
  void visit(std::size_t root, std::vector<std::size_t>& path) {
    struct Frame {
      std::size_t node, next_child;
    };
    std::vector<Frame> stack{{root, 0}};
    path.assign(1, root);
    enter(root, path);
    while (!stack.empty()) {
      Frame& top = stack.back();
      const std::vector<int>& children = model_.nodes[top.node].children;
      if (top.next_child == children.size()) {
        stack.pop_back();
        path.pop_back();
        continue;
      }
      const auto child = static_cast<std::size_t>(children[top.next_child++]);  // checked by check_forest
      if (stack.size() >= max_depth)
        errors_.whole_file("node " + std::to_string(child) + ": nodes nested deeper than " +
                           std::to_string(max_depth) + " levels");
      stack.push_back({child, 0});
      path.push_back(child);
      enter(child, path);
    }
  }

  void enter(std::size_t n, const std::vector<std::size_t>& path) {
    const tinygltf::Node& node = model_.nodes[n];
    if (node.mesh < 0) return;
    if (static_cast<std::size_t>(node.mesh) >= model_.meshes.size())
      errors_.whole_file("node " + std::to_string(n) + ": mesh " + std::to_string(node.mesh) + " does not exist (" +
                         count_of(model_.meshes.size(), "mesh", "meshes") + ")");
    add_mesh(static_cast<std::size_t>(node.mesh), path);
  }

  // The placement of node n, read (and checked) once.
  const Placement& placement(std::size_t n) {
    if (placements_.empty()) placements_.resize(model_.nodes.size());
    if (!placements_[n]) placements_[n] = placement_of(n);
    return *placements_[n];
  }

  // `v` placed by the nodes of `path`, innermost first, each step exact (or the error naming the node).
  // `vertex` and `where` name the vertex in the error only (the message is built only then).
  Vec3 place(Vec3 v, const std::vector<std::size_t>& path, std::size_t vertex, const std::string& where) {
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      const Placement& p = placement(*it);
      double c[3] = {v.x, v.y, v.z};
      for (std::size_t i = 0; i < 3; ++i) {
        const std::optional<double> placed = exact_affine(c[i], p.scale[i], p.translation[i]);
        if (!placed)
          errors_.whole_file("node " + std::to_string(*it) + ": its transform of POSITION " + std::to_string(vertex) +
                             " of " + where + " is not exact in doubles; raykernel applies only exact transforms");
        c[i] = *placed;
      }
      v = {c[0], c[1], c[2]};
    }
    return v;
  }

  Elements elements(int accessor_index, const std::string& where, int type) const {
    if (accessor_index < 0 || static_cast<std::size_t>(accessor_index) >= model_.accessors.size())
      errors_.whole_file(where + ": accessor " + std::to_string(accessor_index) + " does not exist (" +
                         count_of(model_.accessors.size(), "accessor", "accessors") + ")");
    const tinygltf::Accessor& a = model_.accessors[static_cast<std::size_t>(accessor_index)];
    const std::string at = where + " (accessor " + std::to_string(accessor_index) + ")";
    if (a.sparse.isSparse) errors_.whole_file(at + ": sparse accessors are not supported");
    if (a.type != type) errors_.whole_file(at + ": wrong element type");
    const std::size_t component = component_bytes(a.componentType);
    if (component == 0) errors_.whole_file(at + ": unknown component type " + std::to_string(a.componentType));
    Elements e;
    e.count = a.count;
    e.component_type = a.componentType;
    e.size = component * static_cast<std::size_t>(type == TINYGLTF_TYPE_VEC3 ? 3 : 1);
    if (a.bufferView < 0) {  // no buffer view: zeros (glTF 2.0, 3.6.2.1)
      // ... but no more of them than the file has bytes: a few bytes must not make billions of vertices.
      if (e.count > file_size_)
        errors_.whole_file(at + ": " + std::to_string(e.count) + " elements without a buffer view (zeros), more than "
                           "the file has bytes");
      return e;
    }
    if (static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
      errors_.whole_file(at + ": buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model_.buffers.size())
      errors_.whole_file(at + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    std::uint64_t view_end = 0, last = 0, span = 0, end = 0;
    if (!add(view.byteOffset, view.byteLength, view_end) || view_end > buffer.size())
      errors_.whole_file(at + ": its buffer view (bytes " + std::to_string(view.byteOffset) + " + " +
                         std::to_string(view.byteLength) + ") lies outside its buffer (" +
                         std::to_string(buffer.size()) + " bytes)");
    e.stride = view.byteStride == 0 ? e.size : view.byteStride;
    if (e.stride < e.size) errors_.whole_file(at + ": its byte stride is smaller than an element");
    if (e.count > 0 && (!multiply(e.count - 1, e.stride, last) || !add(last, e.size, span) ||
                        !add(a.byteOffset, span, end) || end > view.byteLength))
      errors_.whole_file(at + ": " + std::to_string(e.count) + " elements from byte " + std::to_string(a.byteOffset) +
                         " run past its buffer view (" + std::to_string(view.byteLength) + " bytes)");
    e.data = buffer.data() + view.byteOffset + a.byteOffset;
    return e;
  }

  void add_mesh(std::size_t m, const std::vector<std::size_t>& path) {
    const tinygltf::Mesh& gltf_mesh = model_.meshes[m];
    for (std::size_t k = 0; k < gltf_mesh.primitives.size(); ++k) {
      const tinygltf::Primitive& primitive = gltf_mesh.primitives[k];
      const std::string where = "mesh " + std::to_string(m) + ", primitive " + std::to_string(k);
      const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
      if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) continue;  // points and lines: no surface
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
        errors_.whole_file(where + ": unknown mode " + std::to_string(mode));
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) errors_.whole_file(where + ": no POSITION attribute");
      const Elements p = elements(position->second, where + ": POSITION", TINYGLTF_TYPE_VEC3);
      const tinygltf::Accessor& pa = model_.accessors[static_cast<std::size_t>(position->second)];
      if (p.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT || pa.normalized)
        errors_.whole_file(where + ": POSITION must be float32 (quantized positions are not supported)");
      const std::uint64_t base = mesh_.vertices.size();
      if (base + p.count > max_vertices)
        errors_.whole_file(where + ": more than " + std::to_string(max_vertices) + " vertices in all");
      mesh_.vertices.reserve(base + p.count);
      for (std::size_t v = 0; v < p.count; ++v) {
        float f[3] = {0, 0, 0};
        if (p.data) std::memcpy(f, p.data + v * p.stride, sizeof f);  // glTF is little-endian, as this host
        const Vec3 read{f[0], f[1], f[2]};                             // widened exactly
        for (int i = 0; i < 3; ++i)
          if (!std::isfinite(f[i]))
            errors_.whole_file(where + ": POSITION " + std::to_string(v) + ": " + "xyz"[i] + " is not finite");
        mesh_.vertices.push_back(path.empty() ? read : place(read, path, v, where));
      }
      // The primitive's vertex indices: as stored, or 0, 1, 2, ... without an indices accessor.
      std::vector<std::uint32_t> indices;
      if (primitive.indices >= 0) {
        const Elements ix = elements(primitive.indices, where + ": indices", TINYGLTF_TYPE_SCALAR);
        if (ix.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
            ix.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ix.component_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
          errors_.whole_file(where + ": indices must be unsigned bytes, shorts or ints");
        indices.reserve(ix.count);
        for (std::size_t i = 0; i < ix.count; ++i) {
          std::uint32_t value = 0;
          if (ix.data) {
            unsigned char bytes[4] = {0, 0, 0, 0};
            std::memcpy(bytes, ix.data + i * ix.stride, ix.size);
            value = static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
                    static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
          }
          if (value >= p.count)
            errors_.whole_file(where + ": index " + std::to_string(i) + " is " + std::to_string(value) +
                               ", out of range (" + count_of(p.count, "vertex", "vertices") + ")");
          indices.push_back(value);
        }
      } else {
        indices.resize(p.count);
        for (std::size_t v = 0; v < p.count; ++v) indices[v] = static_cast<std::uint32_t>(v);
      }
      const auto at = [&](std::size_t i) { return static_cast<std::uint32_t>(base + indices[i]); };
      const std::size_t n = indices.size();
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) errors_.whole_file(where + ": " + std::to_string(n) + " indices is not a multiple of 3");
        for (std::size_t i = 0; i + 2 < n; i += 3) mesh_.triangles.push_back({at(i), at(i + 1), at(i + 2)});
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 0; i + 2 < n; ++i)
          mesh_.triangles.push_back({at(i), at(i + 1 + i % 2), at(i + 2 - i % 2)});
      } else {
        for (std::size_t i = 0; i + 2 < n; ++i) mesh_.triangles.push_back({at(i + 1), at(i + 2), at(0)});
      }
    }
  }

  static constexpr std::size_t max_depth = 1000;

  const tinygltf::Model& model_;
  const ErrorSink& errors_;
  std::size_t file_size_;
  std::vector<std::optional<Placement>> placements_;
  Mesh mesh_;
};

// tinygltf's messages, on one line.
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ';');
  return text;
}

}  // namespace

Mesh read_gltf(std::string_view bytes, const ErrorSink& errors, const std::filesystem::path* folder) {
  // JSON numbers through strtod, and the transforms' exactness checks, in the default floating-point environment
  // (round to nearest), whatever the caller left; the caller's is restored on return.
  const DefaultFpEnvironment environment;
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) errors.whole_file("larger than 4 GiB");
  FileAccess access{folder};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&ignore_image, nullptr);
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &access});
  tinygltf::Model model;
  std::string error, warning;
  const std::string base = folder ? folder->string() : std::string();
  const bool binary = bytes.substr(0, 4) == "glTF";
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                           static_cast<unsigned int>(bytes.size()), base)
             : loader.LoadASCIIFromString(&model, &error, &warning, bytes.data(), static_cast<unsigned int>(bytes.size()),
                                          base);
  if (!ok) errors.whole_file("not a valid glTF 2.0 " + std::string(binary ? "binary (GLB)" : "JSON") + " file: " +
                             one_line(error.empty() ? warning : error));
  return Reader(model, errors, bytes.size()).read();
}

#endif

}  // namespace raykernel::io::detail
