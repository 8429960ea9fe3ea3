// Meshes from Python (docs/contract.md §7): raykernel.Mesh, load_mesh (the io readers), and the nearest hit of
// one ray or of arrays of rays through the mesh's BVH (mesh.hpp says why it is built here for now).
#include "mesh.hpp"

#include "batch_support.hpp"
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/io/mesh_file.hpp>

#include <gmp.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::python {
namespace {

// An exact rational from the kernel's decimal strings, for ordering two exact t.
class Mpq {
 public:
  explicit Mpq(const Rational& r) {
    mpq_init(q_);
    mpq_set_str(q_, r.str().c_str(), 10);
    mpq_canonicalize(q_);
  }
  ~Mpq() { mpq_clear(q_); }
  Mpq(const Mpq&) = delete;
  Mpq& operator=(const Mpq&) = delete;
  [[nodiscard]] int compare(const Mpq& other) const { return mpq_cmp(q_, other.q_); }

 private:
  mpq_t q_;
};

// The exact t of a triangle the ray hits (den ≠ 0 there).
Rational exact_t(const Ray& ray, const Triangle& triangle, TriangleRule rule) {
  return *intersect_exact_rational(ray, triangle, rule).t;
}

// Whether the hit (k, t_k) comes before the best so far (best, t_best): smaller exact t, or the same and a
// smaller index. RN is monotone, so different rounded t order the exact ones; equal rounded t are compared
// exactly.
bool before(const Ray& ray, const Mesh& mesh, TriangleRule rule, std::size_t k, double t_k, std::size_t best,
            double t_best) {
  if (t_k != t_best) return t_k < t_best;
  const int order = Mpq(exact_t(ray, mesh.triangle(k), rule)).compare(Mpq(exact_t(ray, mesh.triangle(best), rule)));
  return order < 0 || (order == 0 && k < best);
}

// An upper bound of the exact t whose rounding is t: RN(t) is within half an ulp, so the next double up
// bounds it (inf stays inf).
double exact_upper_bound(double rounded_t) { return std::nextafter(rounded_t, std::numeric_limits<double>::infinity()); }

}  // namespace

PythonMesh::PythonMesh(Mesh mesh) : mesh_(std::move(mesh)), bvh_(mesh_) {}  // MeshBvh validates the mesh

std::optional<MeshHit> nearest_hit(const Ray& ray, const PythonMesh& prepared, TriangleRule rule) {
  const Mesh& mesh = prepared.mesh();
  const TriangleOptions t_only{rule, true, false};  // the winner's coordinates are rounded once, at the end
  std::optional<std::size_t> best;
  double best_t = std::numeric_limits<double>::infinity();
  BvhRayTraversal walk(prepared.bvh(), ray);  // throws invalid_input for an invalid ray
  double bound = std::numeric_limits<double>::infinity();
  while (const std::optional<BvhLeaf> leaf = walk.next(bound)) {
    for (const std::uint32_t k : leaf->triangles) {
      const TriangleIntersection x = intersect(ray, mesh.triangle(k), t_only);
      if (x.relation != TriangleRelation::hit) continue;
      if (!best || before(ray, mesh, rule, k, x.t, *best, best_t)) {
        best = k;
        best_t = x.t;
        bound = exact_upper_bound(best_t);
      }
    }
  }
  if (!best) return std::nullopt;
  return MeshHit{*best, intersect(ray, mesh.triangle(*best), {rule, true, true})};
}

std::optional<MeshHit> nearest_hit_exact(const Ray& ray, const Mesh& mesh, TriangleRule rule) {
  if (const std::optional<std::string> reason = validate(mesh)) throw invalid_input(*reason);
  std::optional<std::size_t> best;
  std::unique_ptr<Mpq> best_t;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const ExactTriangleIntersection x = intersect_exact_rational(ray, mesh.triangle(k), rule);
    if (x.intersection.relation != TriangleRelation::hit) continue;
    auto t = std::make_unique<Mpq>(*x.t);
    if (!best || t->compare(*best_t) < 0) {  // ascending k: an equal t keeps the smaller index
      best = k;
      best_t = std::move(t);
    }
  }
  if (!best) return std::nullopt;
  return MeshHit{*best, intersect_exact(ray, mesh.triangle(*best), {rule, true, true})};
}

namespace {

Mesh mesh_from_arrays(py::handle vertices, py::handle triangles) {
  ColumnsView v(vertices, "vertices");
  Mesh mesh;
  mesh.vertices.reserve(v.rows());
  for (std::size_t i = 0; i < v.rows(); ++i) mesh.vertices.push_back(v.row(i));
  const auto t = py::array_t<std::int64_t, py::array::forcecast>::ensure(triangles);
  if (!t || t.ndim() != 2 || t.shape(1) != 3)
    throw py::value_error("triangles: expected an (m, 3) array of vertex indices");
  const auto r = t.unchecked<2>();
  mesh.triangles.reserve(static_cast<std::size_t>(t.shape(0)));
  for (py::ssize_t k = 0; k < t.shape(0); ++k) {
    std::array<std::uint32_t, 3> tri{};
    for (py::ssize_t j = 0; j < 3; ++j) {
      const std::int64_t index = r(k, j);
      if (index < 0 || index > std::numeric_limits<std::uint32_t>::max())
        throw invalid_input("mesh: triangle " + std::to_string(k) + ": vertex index " + std::to_string(index) +
                            " is out of range (" + std::to_string(mesh.vertices.size()) + " vertices)");
      tri[static_cast<std::size_t>(j)] = static_cast<std::uint32_t>(index);
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

TriangleRule rule_or_owned(py::handle rule) { return rule.is_none() ? TriangleRule::owned : rule_from(rule); }

py::object to_python(const std::optional<MeshHit>& hit) {
  if (!hit) return py::none();
  const TriangleIntersection& x = hit->intersection;
  return types().mesh_hit(hit->triangle, x.t, python::to_python(x.location),
                          types().barycentric(x.barycentric[0], x.barycentric[1], x.barycentric[2]));
}

}  // namespace

py::object nearest_hit_mesh(py::handle ray, const PythonMesh& mesh, py::handle rule, bool exact) {
  const Ray r = ray_from(ray);
  const TriangleRule chosen = rule_or_owned(rule);
  std::optional<MeshHit> hit;
  {
    py::gil_scoped_release release;
    hit = exact ? nearest_hit_exact(r, mesh.mesh(), chosen) : nearest_hit(r, mesh, chosen);
  }
  return to_python(hit);
}

py::object nearest_hit_mesh_batch(py::handle origins, py::handle directions, const PythonMesh& mesh, py::handle rule,
                                  const std::string& path_name, const std::string& errors,
                                  std::optional<unsigned> threads) {
  const Path path = path_from(path_name, false);
  const ErrorPolicy policy = error_policy_from(errors);
  const TriangleRule chosen = rule_or_owned(rule);
  const ColumnsView o(origins, "origins"), d(directions, "directions");
  const std::size_t n = o.rows();
  require_rows(d, "directions", n, "origins");

  auto triangle = new_array<std::int64_t>(n);
  auto t = new_array<double>(n);
  auto location = new_array<std::uint8_t>(n);
  py::array_t<double> barycentric({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  auto valid = new_array<bool>(n);
  const std::span<std::int64_t> triangle_out = span_of(triangle);
  const std::span<double> t_out = span_of(t);
  const std::span<std::uint8_t> location_out = span_of(location);
  const std::span<bool> valid_out = span_of(valid);
  double* const barycentric_out = barycentric.mutable_data();
  std::optional<std::string> error;
  {
    py::gil_scoped_release release;
    // A BVH walk is microseconds per ray, an exact scan far more: small grains.
    parallel_for(n, threads_from(threads), path == Path::exact ? 4 : 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const Ray ray{o.row(i), d.row(i)};
        valid_out[i] = !validate(ray).has_value();
        std::optional<MeshHit> hit;
        if (valid_out[i])
          hit = path == Path::exact ? nearest_hit_exact(ray, mesh.mesh(), chosen) : nearest_hit(ray, mesh, chosen);
        triangle_out[i] = hit ? static_cast<std::int64_t>(hit->triangle) : -1;
        t_out[i] = hit ? hit->intersection.t : nan;
        location_out[i] = hit ? static_cast<std::uint8_t>(hit->intersection.location)
                              : valid_out[i] ? static_cast<std::uint8_t>(TriangleLocation::none) : invalid_code;
        for (std::size_t k = 0; k < 3; ++k) barycentric_out[3 * i + k] = hit ? hit->intersection.barycentric[k] : nan;
      }
    });
    if (const std::optional<std::size_t> i = first_invalid_row(valid_out))
      error = "ray " + std::to_string(*i) + ": " + validate(Ray{o.row(*i), d.row(*i)}).value_or("invalid input");
  }
  if (error && policy == ErrorPolicy::raise) throw invalid_input(*error);
  return types().mesh_hit_arrays(triangle, t, location, barycentric, valid);
}

void bind_mesh(py::module_& m) {
  py::register_exception<io::mesh_file_error>(m, "MeshFileError", PyExc_ValueError)
      .attr("__doc__") = "A file that cannot be read as a mesh: a ValueError whose message names the file, the line "
                         "or byte offset and the reason (\"cube.obj:12: face with fewer than 3 vertices\").";

  py::class_<PythonMesh>(m, "Mesh", R"doc(A triangle mesh (docs/contract.md §7), validated once, with its BVH.

``Mesh(vertices, triangles)``: an (n, 3) float64 array of vertices, taken exactly, and an (m, 3) integer array
of vertex indices counted from 0. Nothing is welded, moved or dropped; degenerate triangles are kept (never
hit). Raises ``ValueError`` naming the first bad vertex or triangle ("mesh: vertex 7: y is not finite", "mesh:
triangle 3: vertex index 12 is out of range (10 vertices)"). ``load_mesh(path)`` reads one from a file.)doc")
      .def(py::init([](py::handle vertices, py::handle triangles) {
             Mesh mesh = mesh_from_arrays(vertices, triangles);
             py::gil_scoped_release release;
             return PythonMesh(std::move(mesh));
           }),
           py::arg("vertices"), py::arg("triangles"))
      .def("__len__", [](const PythonMesh& s) { return s.mesh().triangles.size(); })
      .def_property_readonly(
          "vertices",
          [](const PythonMesh& s) {
            const auto& v = s.mesh().vertices;
            py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
            double* out = a.mutable_data();
            for (std::size_t i = 0; i < v.size(); ++i) out[3 * i] = v[i].x, out[3 * i + 1] = v[i].y, out[3 * i + 2] = v[i].z;
            return a;
          },
          "The vertices, a new (n, 3) float64 array.")
      .def_property_readonly(
          "triangles",
          [](const PythonMesh& s) {
            const auto& t = s.mesh().triangles;
            py::array_t<std::int64_t> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}});
            std::int64_t* out = a.mutable_data();
            for (std::size_t k = 0; k < t.size(); ++k)
              for (std::size_t j = 0; j < 3; ++j) out[3 * k + j] = t[k][j];
            return a;
          },
          "The triangles' vertex indices, a new (m, 3) int64 array.")
      .def(
          "triangle",
          [](const PythonMesh& s, py::ssize_t k) {
            const auto m = static_cast<py::ssize_t>(s.mesh().triangles.size());
            if (k < 0) k += m;
            if (k < 0 || k >= m) throw py::index_error("triangle index out of range");
            const Triangle t = s.mesh().triangle(static_cast<std::size_t>(k));
            return types().triangle(python::to_python(t.a), python::to_python(t.b), python::to_python(t.c));
          },
          py::arg("index"), "Triangle ``index`` as a ``raykernel.Triangle`` (its vertices in the stored order).")
      .def_property_readonly("bvh_depth", [](const PythonMesh& s) { return s.bvh().depth(); },
                             "The depth of the mesh's BVH.")
      .def("__repr__", [](const PythonMesh& s) {
        return "Mesh(" + std::to_string(s.mesh().vertices.size()) + " vertices, " +
               std::to_string(s.mesh().triangles.size()) + " triangles)";
      });

  m.def(
      "load_mesh",
      [](const std::string& path) {
        Mesh mesh;
        {
          py::gil_scoped_release release;
          mesh = io::read_mesh(std::filesystem::path(path));
        }
        py::gil_scoped_release release;
        return PythonMesh(std::move(mesh));
      },
      py::arg("path"),
      R"doc(The mesh in the file at ``path`` (OBJ, PLY, STL or OFF: the extension's format, else the content's),
read exactly: decimal coordinates correctly rounded, binary ones widened exactly, polygons fanned from their
first vertex (docs/contract.md §7). Raises ``raykernel.MeshFileError`` (a ValueError) naming the file, the
line or byte offset and the reason. Releases the GIL.)doc");

  // inside(point, mesh) (docs/contract.md §7) goes here when the kernel's inside() (branch mesh2,
  // <raykernel/mesh_queries.hpp>) is on main: a thin binding like nearest_hit's, scalar and over arrays.
}

}  // namespace raykernel::python
