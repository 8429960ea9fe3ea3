// Meshes from Python (docs/contract.md §7): raykernel.Mesh, load_mesh (the io readers), and the kernel's mesh
// queries (<raykernel/mesh_queries.hpp>) for one ray or point and over arrays of them, on threads.
#include "mesh.hpp"

#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"
#include "ray_batch.hpp"
#include "sphere_set.hpp"

#include <raykernel/io/mesh_file.hpp>
#include <raykernel/occlusion.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

namespace raykernel::python {
namespace {

// Reads the (m, 3) indices of `triangles` as Index (int64 or uint64: every integer dtype widens to one of them
// exactly), each checked as the integer it is against [0, vertex count) — never wrapped (uint64 max is not −1)
// nor narrowed to the mesh's uint32 before the check.
template <class Index>
void read_triangles(const py::array& triangles, Mesh& mesh) {
  const auto t = py::array_t<Index, py::array::forcecast>::ensure(triangles);
  if (!t) throw py::type_error(std::string("triangles: the array cannot be read as ") +
                               (std::is_signed_v<Index> ? "int64" : "uint64"));  // out of memory
  const auto r = t.template unchecked<2>();
  const std::size_t vertex_count = mesh.vertices.size();
  mesh.triangles.reserve(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t k = 0; k < t.shape(0); ++k) {
    std::array<std::uint32_t, 3> tri{};
    for (py::ssize_t j = 0; j < 3; ++j) {
      const Index index = r(k, j);
      const std::string where = "mesh: triangle " + std::to_string(k) + ": vertex index " + std::to_string(index) +
                                " (triangles[" + std::to_string(k) + ", " + std::to_string(j) + "])";
      bool negative = false;
      if constexpr (std::is_signed_v<Index>) negative = index < 0;
      if (negative || static_cast<std::uint64_t>(index) >= vertex_count)
        throw invalid_input(where + " is out of range (" + std::to_string(vertex_count) + " vertices)");
      if (static_cast<std::uint64_t>(index) > std::numeric_limits<std::uint32_t>::max())
        throw invalid_input(where + " is beyond 2^32 - 1, the largest index a mesh stores");
      tri[static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(index);
    }
    mesh.triangles.push_back(tri);
  }
}

Mesh mesh_from_arrays(py::handle vertices, py::handle triangles) {
  ColumnsView v(vertices, "vertices");
  Mesh mesh;
  mesh.vertices.reserve(v.rows());
  for (std::size_t i = 0; i < v.rows(); ++i) mesh.vertices.push_back(v.row(i));
  // Integer dtypes only: a float index is refused rather than truncated (1.9 → 1, −0.5 → 0, NaN → −2^63).
  const py::array t =
      numeric_array(triangles, "triangles", Numbers::integer, "an (m, 3) array of integer vertex indices");
  if (t.ndim() != 2 || t.shape(1) != 3)
    throw py::value_error("triangles: expected an (m, 3) array of vertex indices, got shape " + shape_string(t));
  if (t.dtype().kind() == 'u')
    read_triangles<std::uint64_t>(t, mesh);
  else
    read_triangles<std::int64_t>(t, mesh);  // signed, or an empty array of a floating dtype
  return mesh;
}

}  // namespace

const PythonMesh& mesh_from(py::handle scene, const char* wanted) {
  if (!py::isinstance<PythonMesh>(scene))
    throw py::type_error(std::string("scene: expected ") + wanted + ", got " + Py_TYPE(scene.ptr())->tp_name);
  return scene.cast<const PythonMesh&>();
}

py::object to_python(const std::optional<MeshHit>& hit) {
  if (!hit) return py::none();
  const TriangleIntersection& x = hit->intersection;
  return types().mesh_hit(hit->triangle, x.t, python::to_python(x.location),
                          types().barycentric(x.barycentric.a, x.barycentric.b, x.barycentric.c));
}

namespace {

// The kernel's answer on `path` within `interval` (the naive path has no rule). Throws invalid_input for an
// invalid ray or interval.
std::optional<MeshHit> nearest_on(Path path, const Ray& ray, const RayInterval& interval, const PythonMesh& mesh,
                                  TriangleRule rule) {
  switch (path) {
    case Path::exact:
      return nearest_hit_exact(ray, interval, mesh.mesh(), rule);
    case Path::naive:
      return nearest_hit_naive(ray, interval, mesh.prepared());
    case Path::certified:
      break;
  }
  return nearest_hit(ray, interval, mesh.prepared(), rule);
}

}  // namespace

py::object nearest_hit_mesh(py::handle ray, const PythonMesh& mesh, double t_min, double t_max, py::handle rule,
                            Path path) {
  if (path == Path::naive && !rule.is_none()) throw py::value_error("rule: the naive path has no rule");
  const Ray r = ray_from(ray);
  const RayInterval interval{t_min, t_max};
  const TriangleRule chosen = rule_or_owned(rule);
  std::optional<MeshHit> hit;
  {
    py::gil_scoped_release release;
    hit = nearest_on(path, r, interval, mesh, chosen);
  }
  return to_python(hit);
}

py::object nearest_hit_mesh_batch(py::handle origins, py::handle directions, const PythonMesh& mesh, py::handle t_min,
                                  py::handle t_max, py::handle rule, const std::string& path_name,
                                  const std::string& errors, std::optional<unsigned> threads) {
  const RayRows b(origins, directions, t_min, t_max, rule, path_name, errors, /*allow_naive=*/true);
  if (b.path == Path::naive && !rule.is_none()) throw py::value_error("rule: the naive path has no rule");
  const std::size_t n = b.rows();
  auto triangle = new_array<std::int64_t>(n);
  auto t = new_array<double>(n);
  auto location = new_array<std::uint8_t>(n);
  py::array_t<double> barycentric({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto valid = new_array<bool>(n);
  const std::span<std::int64_t> triangle_out = span_of(triangle);
  const std::span<double> t_out = span_of(t);
  const std::span<std::uint8_t> location_out = span_of(location);
  double* const barycentric_out = barycentric.mutable_data();
  // A BVH walk is microseconds per ray, an exact scan far more: small grains.
  b.run(span_of(valid), threads, b.exact ? 4 : 256,
        [&](std::size_t i, const Ray& ray, const RayInterval& interval, bool ok) {
          std::optional<MeshHit> hit;
          if (ok) hit = nearest_on(b.path, ray, interval, mesh, b.rule);
          triangle_out[i] = hit ? static_cast<std::int64_t>(hit->triangle) : -1;
          t_out[i] = hit ? hit->intersection.t : nan;
          location_out[i] = hit  ? static_cast<std::uint8_t>(hit->intersection.location)
                            : ok ? static_cast<std::uint8_t>(TriangleLocation::none)
                                 : invalid_code;
          for (std::size_t k = 0; k < 3; ++k) barycentric_out[3 * i + k] = hit ? hit->intersection.barycentric[k] : nan;
        });
  return types().mesh_hit_arrays(triangle, t, location, barycentric, valid);
}

namespace {

py::object to_python(PointLocation location) { return types().point_location[static_cast<std::size_t>(location)]; }

py::object inside_py(py::handle point, const PythonMesh& mesh, bool exact) {
  const Vec3 p = vec3_from(point, "point");
  PointLocation location{};
  {
    py::gil_scoped_release release;
    location = exact ? inside_exact(p, mesh.mesh()) : inside(p, mesh.prepared());
  }
  return to_python(location);
}

shown::PointLocationArrays inside_batch_py(shown::ArrayLike3 points, const PythonMesh& mesh,
                                           const std::string& path_name, const std::string& errors,
                                           std::optional<unsigned> threads) {
  const bool exact = path_from(path_name, false) == Path::exact;
  const ErrorPolicy policy = error_policy_from(errors);
  const ColumnsView p(points, "points");
  const std::size_t n = p.rows();
  auto location = new_array<std::uint8_t>(n);
  auto valid = new_array<bool>(n);
  const std::span<std::uint8_t> location_out = span_of(location);
  const std::span<bool> valid_out = span_of(valid);
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    // A BVH walk is microseconds per point, an exact scan microseconds per triangle: small grains.
    parallel_for(n, threads_from(threads), exact ? 4 : 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 point = p.row(i);
        valid_out[i] = !point_problem(point).has_value();
        location_out[i] = !valid_out[i] ? invalid_code
                          : static_cast<std::uint8_t>(exact ? inside_exact(point, mesh.mesh())
                                                            : inside(point, mesh.prepared()));
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid_out))
      error = "point " + std::to_string(*i) + ": " + point_problem(p.row(*i)).value_or("invalid input");
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().point_location_arrays(location, valid);
}

}  // namespace

namespace {

// A mesh_file_error thrown where the file does not exist (load_mesh): MeshFileNotFoundError in Python.
class MeshFileNotFound : public io::mesh_file_error {
 public:
  using io::mesh_file_error::mesh_file_error;
};

// Sets the Python error raykernel._types.<type_name>(message, file, line, byte_offset, reason) for `e`.
void raise_mesh_file_error(const io::mesh_file_error& e, const char* type_name) {
  const py::object type = py::module_::import("raykernel._types").attr(type_name);
  const io::FilePosition& at = e.position();
  const py::object line = at.kind == io::FilePosition::Kind::line ? py::object(py::int_(at.value)) : py::none();
  const py::object offset =
      at.kind == io::FilePosition::Kind::byte_offset ? py::object(py::int_(at.value)) : py::none();
  // The file name as the caller wrote it: the bytes of a path decoded as os.fsdecode does (surrogateescape).
  const py::object file = py::module_::import("os").attr("fsdecode")(py::bytes(e.file()));
  const py::object message = py::reinterpret_steal<py::object>(
      PyUnicode_DecodeFSDefaultAndSize(e.what(), static_cast<Py_ssize_t>(std::strlen(e.what()))));
  if (!message) throw py::error_already_set();
  const py::object instance = type(message, file, line, offset, py::str(e.reason()));
  PyErr_SetObject(type.ptr(), instance.ptr());
}

py::array_t<double> vertices_array(const PythonMesh& s) {
  const auto& v = s.mesh().vertices;
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  double* out = a.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) out[3 * i] = v[i].x, out[3 * i + 1] = v[i].y, out[3 * i + 2] = v[i].z;
  return a;
}

py::array_t<std::int64_t> triangles_array(const PythonMesh& s) {
  const auto& t = s.mesh().triangles;
  py::array_t<std::int64_t> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
  std::int64_t* out = a.mutable_data();
  for (std::size_t k = 0; k < t.size(); ++k)
    for (std::size_t j = 0; j < 3; ++j) out[3 * k + j] = t[k][j];
  return a;
}

// The mesh in the file at `path` (str, bytes or os.PathLike), for load_mesh.
PythonMesh load_mesh_py(const shown::PathLike& path) {
  // os.fsencode: the path's bytes as the OS takes them (a str encoded as open() encodes it; TypeError for
  // anything that is not a path).
  const std::string raw = py::module_::import("os").attr("fsencode")(path).cast<std::string>();
  // The file APIs end a path at its first NUL: "a.off\0b" would open a.off. Python's open() refuses such a path
  // (ValueError "embedded null byte"); so does this, as the MeshFileError of a file that cannot be read, with the
  // NUL shown as \0 (the message is a C string: a raw NUL would cut it short).
  if (raw.find('\0') != std::string::npos) {
    std::string shown;
    for (const char c : raw) shown += c == '\0' ? std::string("\\0") : std::string(1, c);
    throw io::mesh_file_error(shown, {}, "the path contains a NUL character, which no file name can");
  }
  py::gil_scoped_release release;
  const std::filesystem::path file(raw);
  Mesh mesh;
  try {
    mesh = io::read_mesh(file);
  } catch (const io::mesh_file_error& e) {
    std::error_code ec;
    if (e.position().kind == io::FilePosition::Kind::none &&
        std::filesystem::status(file, ec).type() == std::filesystem::file_type::not_found)
      throw MeshFileNotFound(e.file(), e.position(), e.reason());
    throw;
  }
  try {
    return PythonMesh(std::move(mesh));
  } catch (const invalid_input& e) {
    // The readers check what validating the mesh checks (indices in range, finite coordinates), so this is a
    // reader's miss; it is still the file's problem, and reported as one: "FILE: mesh: triangle 0: ...".
    throw io::mesh_file_error(raw, {}, e.what());
  }
}

}  // namespace

void bind_mesh(py::module_& m) {
  // MeshFileError and MeshFileNotFoundError are Python classes (raykernel._types: attributes, pickling); every
  // mesh_file_error that reaches Python becomes one of them.
  const py::module_ types_module = py::module_::import("raykernel._types");
  m.attr("MeshFileError") = types_module.attr("MeshFileError");
  m.attr("MeshFileNotFoundError") = types_module.attr("MeshFileNotFoundError");
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const MeshFileNotFound& e) {
      raise_mesh_file_error(e, "MeshFileNotFoundError");
    } catch (const io::mesh_file_error& e) {
      raise_mesh_file_error(e, "MeshFileError");
    }
  });

  py::class_<PythonMesh>(m, "Mesh",
                         R"doc(A triangle mesh (docs/contract.md §7), validated once, with its BVH built once.

``Mesh(vertices, triangles)``: an (n, 3) array of vertices (real numbers, read as float64: a float64 array is
taken exactly), and an (m, 3) array of vertex indices counted from 0, of any integer dtype (int8 to uint64;
lists of ints). Float indices are refused, integral or not (``TypeError``: they would be truncated), as are
bool, complex, str, object and masked arrays; each index is checked as the integer it is, never wrapped
(uint64 2^64 − 1 is not −1). Nothing is welded, moved or dropped; degenerate triangles are kept (never hit).
Raises ``ValueError`` (``InvalidInput``) naming the first bad vertex or index ("mesh: vertex 7: y is not
finite", "mesh: triangle 3: vertex index 12 (triangles[3, 1]) is out of range (10 vertices)").
``load_mesh(path)`` reads one from a file.)doc")
      .def(py::init([](shown::ArrayLike3 vertices, shown::ArrayLike triangles) {
             Mesh mesh = mesh_from_arrays(vertices, triangles);
             py::gil_scoped_release release;
             return PythonMesh(std::move(mesh));
           }),
           py::arg("vertices"), py::arg("triangles"))
      .def("__len__", [](const PythonMesh& s) { return s.mesh().triangles.size(); })
      .def_property_readonly("vertices", &vertices_array, "The vertices, a new (n, 3) float64 array.")
      .def_property_readonly("triangles", &triangles_array, "The triangles' vertex indices, a new (m, 3) int64 array.")
      // A Mesh pickles as its vertices and triangles (float64 and int64: exact), and unpickling prepares it
      // again (the BVH is rebuilt, deterministically: the same answers), so that it travels to other processes
      // (multiprocessing, Dask workers: raykernel.dask).
      .def(py::pickle([](const PythonMesh& s) { return py::make_tuple(vertices_array(s), triangles_array(s)); },
                      [](const py::tuple& state) {
                        if (state.size() != 2) throw py::value_error("Mesh: a pickled state is (vertices, triangles)");
                        Mesh mesh = mesh_from_arrays(state[0], state[1]);
                        py::gil_scoped_release release;
                        return PythonMesh(std::move(mesh));
                      }))
      .def(
          "triangle",
          [](const PythonMesh& s, py::ssize_t k) -> shown::Triangle {
            const auto m = static_cast<py::ssize_t>(s.mesh().triangles.size());
            if (k < 0) k += m;
            if (k < 0 || k >= m) throw py::index_error("triangle index out of range");
            const Triangle t = s.mesh().triangle(static_cast<std::size_t>(k));
            return types().triangle(python::to_python(t.a), python::to_python(t.b), python::to_python(t.c));
          },
          py::arg("index"), "Triangle ``index`` as a ``raykernel.Triangle`` (its vertices in the stored order).")
      .def_property_readonly(
          "bvh_depth", [](const PythonMesh& s) { return s.prepared().bvh().depth(); }, "The depth of the mesh's BVH.")
      .def("__repr__", [](const PythonMesh& s) {
        return "Mesh(" + std::to_string(s.mesh().vertices.size()) + " vertices, " +
               std::to_string(s.mesh().triangles.size()) + " triangles)";
      });

  m.def(
      "load_mesh", &load_mesh_py,
      py::arg("path"),
      R"doc(The mesh in the file at ``path`` (OBJ, PLY, STL, OFF or glTF: the extension's format, else the content's),
read exactly: decimal coordinates correctly rounded, binary ones widened exactly, polygons fanned from their
first vertex (docs/contract.md §7). ``path`` is a str, bytes or any ``os.PathLike`` (``pathlib.Path``).
Raises ``raykernel.MeshFileError`` (a ValueError) naming the file, the line or byte offset and the reason, each
also an attribute (``file``, ``line``, ``byte_offset``, ``reason``) — for every file that cannot be read as a
mesh, and for a path containing a NUL character, which ``open()`` refuses too; where there is no file,
``raykernel.MeshFileNotFoundError``, which is also a ``FileNotFoundError``; ``TypeError`` for a ``path`` that is
not a path. Releases the GIL.)doc");

  m.def(
      "mesh_bytes",
      [](const PythonMesh& mesh, const std::string& format, const std::string& encoding) {
        io::MeshFormat f{};
        if (format == "obj") f = io::MeshFormat::obj;
        else if (format == "ply") f = io::MeshFormat::ply;
        else if (format == "stl") f = io::MeshFormat::stl;
        else if (format == "off") f = io::MeshFormat::off;
        else if (format == "gltf") f = io::MeshFormat::gltf;
        else throw py::value_error("format: expected 'obj', 'ply', 'stl', 'off' or 'gltf', got '" + format + "'");
        io::MeshEncoding e{};
        if (encoding == "ascii") e = io::MeshEncoding::ascii;
        else if (encoding == "binary") e = io::MeshEncoding::binary_little_endian;
        else if (encoding == "binary_big_endian") e = io::MeshEncoding::binary_big_endian;
        else throw py::value_error("encoding: expected 'ascii', 'binary' or 'binary_big_endian', got '" + encoding + "'");
        std::string bytes;
        {
          py::gil_scoped_release release;
          bytes = io::write_mesh(mesh.mesh(), f, e);  // std::invalid_argument: ValueError
        }
        return py::bytes(bytes);
      },
      py::arg("mesh"), py::arg("format"), py::kw_only(), py::arg("encoding") = "ascii",
      R"doc(The mesh as the bytes of a file in ``format`` ("obj", "ply", "stl", "off"), exactly: text formats print each
coordinate as the shortest decimal that reads back as the same double, PLY binary stores doubles, so
``load_mesh`` of the written file gives the same vertices and triangles bit for bit (STL has no indices: its
vertices come back unshared; STL binary stores floats and is refused unless every coordinate is one). ``encoding``:
"ascii", "binary" (little-endian; PLY, STL) or "binary_big_endian" (PLY). Raises ``ValueError`` for a combination
the format does not have, and for glTF (float32 positions cannot hold every double). ``save_mesh`` writes it to a
file.)doc");

  m.def(
      "inside",
      [](shown::Vec3Like point, const PythonMesh& mesh) -> shown::PointLocation {
        return inside_py(point, mesh, false);
      },
      py::arg("point"), py::arg("mesh"),
      R"doc(Where ``point`` is against ``mesh`` (docs/contract.md §7), exactly: ``PointLocation.ON_SURFACE`` if it
lies on some triangle (closed: edges and vertices included), else ``INSIDE`` if the exact winding number is
nonzero (outward or inward normals alike), else ``OUTSIDE``. The winding number is the signed count of the
owned crossings (docs/contract.md §6) of an axis-aligned ray from the point, found through the mesh's BVH; for a
closed, consistently oriented mesh it does not depend on the ray, and the answer is ``inside_exact``'s. Raises
``ValueError`` for a non-finite point ("point x is not finite"). Releases the GIL.)doc");

  m.def(
      "inside_exact",
      [](shown::Vec3Like point, const PythonMesh& mesh) -> shown::PointLocation {
        return inside_py(point, mesh, true);
      },
      py::arg("point"), py::arg("mesh"),
      R"doc(The reference ``inside``: every triangle in exact rationals (the on-surface test and the crossings of
the same ray), no BVH. Slow and obviously right; the same answer as ``inside``. Releases the GIL.)doc");

  m.def(
      "occluded",
      [](shown::RayLike ray, shown::MeshOrSpheres scene, double t_min, double t_max, shown::OptionalRule rule,
         const std::string& path) {
        const Ray r = ray_from(ray);
        const RayInterval interval{t_min, t_max};
        const bool exact = path_from(path, false) == Path::exact;
        if (is_sphere_set(scene)) {
          require_no_rule(rule, scene);
          if (auto reason = ray_problem(r, interval)) throw invalid_input(*reason);
          const auto& spheres = scene.cast<const raykernel::SphereSet&>();
          py::gil_scoped_release release;
          return occluded_spheres(r, interval, spheres, exact);
        }
        const PythonMesh& mesh = mesh_from(scene, "a raykernel.Mesh or a raykernel.SphereSet");
        const TriangleRule chosen = rule_or_owned(rule);
        py::gil_scoped_release release;
        return exact ? occluded_exact(r, interval, mesh.mesh(), chosen) : occluded(r, interval, mesh.prepared(), chosen);
      },
      py::arg("ray"), py::arg("scene"), py::kw_only(), py::arg("t_min") = 0.0,
      py::arg("t_max") = std::numeric_limits<double>::infinity(), py::arg("rule") = py::none(),
      py::arg("path") = "certified",
      R"doc(Whether some triangle of ``scene`` (a ``Mesh``) blocks ``ray`` within ``[t_min, t_max]``
(docs/contract.md §8): a triangle whose relation under ``rule`` (owned by default) is hit at an exact t with
``t_min <= t <= t_max``, compared exactly (never a rounded t); coplanar and degenerate triangles never block. A
``SphereSet`` blocks where a sphere has a root in the interval (§10: closed, the tangent root included; no rule).
Any-hit: stops at the first blocker. ``path``: "certified" (through the BVH) or "exact" (every triangle or
sphere in rationals). Raises ``ValueError`` for an invalid ray or interval, naming the bound ("t_min is greater
than t_max"). Releases the GIL.)doc");

  m.def(
      "occluded_segment",
      [](shown::Vec3Like p, shown::Vec3Like q, shown::MeshOrSpheres scene, shown::OptionalRule rule,
         const std::string& path) {
        const Vec3 a = vec3_from(p, "p"), b = vec3_from(q, "q");
        const bool exact = path_from(path, false) == Path::exact;
        if (is_sphere_set(scene)) {
          require_no_rule(rule, scene);
          if (auto reason = validate_segment(a, b)) throw invalid_input(*reason);
          const auto& spheres = scene.cast<const raykernel::SphereSet&>();
          py::gil_scoped_release release;
          return occluded_segment_spheres(a, b, spheres, exact);
        }
        const PythonMesh& mesh = mesh_from(scene, "a raykernel.Mesh or a raykernel.SphereSet");
        const TriangleRule chosen = rule_or_owned(rule);
        py::gil_scoped_release release;
        return exact ? occluded_exact(a, b, mesh.mesh(), chosen) : occluded(a, b, mesh.prepared(), chosen);
      },
      py::arg("p"), py::arg("q"), py::arg("scene"), py::kw_only(), py::arg("rule") = py::none(),
      py::arg("path") = "certified",
      R"doc(Whether some triangle of ``scene`` (a ``Mesh``, or sphere of a ``SphereSet``) meets the open segment
between the points ``p`` and ``q``
(docs/contract.md §8): 0 < t < 1 along the exact direction ``q - p``, which is not rounded; the endpoints never
count, and under the owned rule (the default) a segment through a shared edge or vertex of a closed mesh is
blocked by exactly one triangle. ``path``: "certified" or "exact". Raises ``ValueError`` for a non-finite
coordinate or ``p == q``. Releases the GIL.)doc");

  m.def("inside_batch", with_progress(&inside_batch_py), py::arg("points"), py::arg("mesh"), py::kw_only(),
        py::arg("path") = "certified", py::arg("errors") = "raise", py::arg("threads") = py::none(), py::arg("progress") = py::none(),
        R"doc(``inside`` over an (n, 3) array of points (real numbers, read as float64), on threads, with the GIL
released.

Returns ``PointLocationArrays(location, valid)``: ``location`` uint8 ``PointLocation.code`` per row
(``INVALID_RELATION_CODE`` where the point is not finite), ``valid`` bool. ``path``: "certified" (``inside``,
through the BVH) or "exact" (``inside_exact``). ``errors``: "raise" (default) raises ``ValueError`` naming the
first bad row, "point 17: y is not finite"; "mask" answers the others and marks it in ``valid``. ``threads``:
None for all cores, or a count.

Ctrl-C stops a long call (``KeyboardInterrupt``, within a block of rows); ``progress``, None or a callable, is
called with (done, total) about every 0.1 s and at the end (an exception it raises stops the call too).)doc");
}

}  // namespace raykernel::python
