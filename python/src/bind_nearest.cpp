// PlaneSet and the scalar nearest hit (docs/contract.md §4): the first plane one ray meets.
#include "bindings.hpp"
#include "convert.hpp"
#include "mesh.hpp"
#include "plane_set.hpp"
#include "sphere_set.hpp"

#include <raykernel/nearest_hit.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace raykernel::python {
namespace {

// Below this many planes a nearest hit takes well under a microsecond: not worth releasing the GIL.
constexpr std::size_t release_gil_above_planes = 64;

template <class F>
py::object nearest(py::handle ray, py::handle planes, F&& search) {
  const Ray r = ray_from(ray);
  std::optional<raykernel::PlaneSet> storage;
  const raykernel::PlaneSet& set = planes_from(planes, storage);
  std::optional<NearestHit> hit;
  if (set.size() > release_gil_above_planes) {
    py::gil_scoped_release release;
    hit = search(r, set);
  } else {
    hit = search(r, set);
  }
  return to_python(hit);
}

std::vector<Plane> read_planes(py::handle planes_or_points, py::handle normals) {
  std::vector<Plane> planes;
  if (normals.is_none()) {
    if (!PySequence_Check(planes_or_points.ptr()) || PyUnicode_Check(planes_or_points.ptr()))
      throw py::type_error("planes: expected a raykernel.PlaneSet or a sequence of (point, normal) pairs, got " +
                           std::string(Py_TYPE(planes_or_points.ptr())->tp_name));
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(planes_or_points);
    const std::size_t m = py::len(planes_or_points);
    planes.reserve(m);
    for (std::size_t k = 0; k < m; ++k) planes.push_back(plane_from(seq[k], "plane " + std::to_string(k)));
  } else {
    ColumnsView points(planes_or_points, "points"), ns(normals, "normals");
    require_rows(ns, "normals", points.rows(), "points");
    planes.reserve(points.rows());
    for (std::size_t k = 0; k < points.rows(); ++k) planes.push_back({points.row(k), ns.row(k)});
  }
  return planes;
}

}  // namespace

PlaneSet::PlaneSet(py::handle planes_or_points, py::handle normals)
    : prepared_(read_planes(planes_or_points, normals)) {}

const raykernel::PlaneSet& planes_from(py::handle value, std::optional<raykernel::PlaneSet>& storage) {
  if (py::isinstance<PlaneSet>(value)) return value.cast<const PlaneSet&>().prepared();
  storage.emplace(read_planes(value, py::none()));
  return *storage;
}

// The planes' points or normals (`member`), a new (m, 3) array.
py::array_t<double> plane_columns(const PlaneSet& s, Vec3 Plane::*member) {
  py::array_t<double> a({static_cast<py::ssize_t>(s.planes().size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t k = 0; k < s.planes().size(); ++k) {
    const Vec3& v = s.planes()[k].*member;
    const auto i = static_cast<py::ssize_t>(k);
    w(i, 0) = v.x, w(i, 1) = v.y, w(i, 2) = v.z;
  }
  return a;
}

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// nearest_hit (exact = false) and nearest_hit_exact (true) on any scene: the scene's kind chooses the query, `exact`
// its reference. The exact plane scan always releases the GIL (microseconds per plane).
py::object nearest_in_scene(py::handle ray, py::handle scene, py::handle rule, double t_min, double t_max, bool exact) {
  if (py::isinstance<PythonMesh>(scene))
    return nearest_hit_mesh(ray, scene.cast<const PythonMesh&>(), t_min, t_max, rule,
                            exact ? Path::exact : Path::certified);
  require_no_rule(rule, scene);
  if (is_sphere_set(scene))
    return nearest_hit_spheres(ray, scene.cast<const raykernel::SphereSet&>(), t_min, t_max, exact);
  const RayInterval interval{t_min, t_max};
  if (!exact)
    return nearest(ray, scene, [&](const Ray& r, const raykernel::PlaneSet& p) { return nearest_hit(r, interval, p); });
  const Ray r = ray_from(ray);
  std::optional<raykernel::PlaneSet> storage;
  const raykernel::PlaneSet& set = planes_from(scene, storage);
  std::optional<NearestHit> hit;
  {
    py::gil_scoped_release release;
    hit = nearest_hit_exact(r, interval, set.planes());
  }
  return to_python(hit);
}

}  // namespace

void bind_nearest(py::module_& m) {
  py::class_<PlaneSet>(m, "PlaneSet", R"doc(The planes of a scene, read and validated once.

``PlaneSet(planes)`` takes a sequence of ``(point, normal)`` pairs (e.g. ``raykernel.Plane`` values);
``PlaneSet(points, normals)`` takes two (m, 3) arrays of real numbers (read as float64). Plane k is the k-th, counted from 0: the index
``nearest_hit`` answers. Raises ``ValueError`` naming the first invalid plane
(``"plane 3: plane normal is the zero vector"``). Pass it to ``nearest_hit`` and ``nearest_hit_batch``
instead of a list to prepare the planes once: they are validated once, and each plane that coincides exactly
with an earlier one is set aside once (``candidates``), so a query tests only the planes that can win.)doc")
      .def(py::init([](shown::PlanesOrArray planes, shown::OptionalArrayLike3 normals) {
             return PlaneSet(planes, normals);
           }),
           py::arg("planes"), py::arg("normals") = py::none())
      .def("__len__", [](const PlaneSet& s) { return s.planes().size(); })
      .def(
          "__getitem__",
          [](const PlaneSet& s, py::ssize_t k) -> shown::Plane {
            const auto m = static_cast<py::ssize_t>(s.planes().size());
            if (k < 0) k += m;
            if (k < 0 || k >= m) throw py::index_error("plane index out of range");
            return to_python(s.planes()[static_cast<std::size_t>(k)]);
          },
          py::arg("index"))
      .def_property_readonly(
          "points", [](const PlaneSet& s) { return plane_columns(s, &Plane::point); },
          "The planes' points, a new (m, 3) array.")
      .def_property_readonly(
          "normals", [](const PlaneSet& s) { return plane_columns(s, &Plane::normal); },
          "The planes' normals, a new (m, 3) array.")
      // A PlaneSet pickles as (points, normals), exactly (float64), and is prepared again when unpickled, so that
      // it travels to other processes (raykernel.dask).
      .def(py::pickle(
          [](const PlaneSet& s) {
            return py::make_tuple(plane_columns(s, &Plane::point), plane_columns(s, &Plane::normal));
          },
          [](const py::tuple& state) {
            if (state.size() != 2) throw py::value_error("PlaneSet: a pickled state is (points, normals)");
            return PlaneSet(state[0], state[1]);
          }))
      .def_property_readonly(
          "candidates",
          [](const PlaneSet& s) {
            const auto c = s.prepared().candidates();
            py::array_t<std::uint32_t> a(static_cast<py::ssize_t>(c.size()));
            std::copy(c.begin(), c.end(), a.mutable_data());
            return a;
          },
          "The indices of the planes that can win a nearest hit, ascending: each plane not coinciding exactly\n"
          "with an earlier one (a new uint32 array). A coinciding plane has the same t as the earlier one for\n"
          "every ray, so it never wins (ties go to the smallest index).")
      .def("__repr__", [](const PlaneSet& s) { return "PlaneSet(" + std::to_string(s.planes().size()) + " planes)"; });

  m.def(
      "nearest_hit",
      [](shown::RayLike ray, shown::Scene scene, shown::OptionalRule rule, double t_min,
         double t_max) -> shown::NearestHit { return nearest_in_scene(ray, scene, rule, t_min, t_max, false); },
      py::arg("ray"), py::arg("scene"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t_min") = 0.0,
      py::arg("t_max") = inf,
      R"doc(The first plane, triangle or sphere ``ray`` meets, decided exactly, or None.

Planes (``scene`` a ``PlaneSet`` or a sequence of ``(point, normal)`` pairs; docs/contract.md §4): among the
planes whose relation is HIT (t ≥ 0), the one with the smallest exact t = num/den, ties to the smallest index:
``NearestHit(plane, t)``, ``t`` rounded as ``intersect`` rounds it. t values are compared exactly, never after
rounding, so planes closer than an ulp are ordered right.

Mesh (``scene`` a ``raykernel.Mesh``; docs/contract.md §7): among the triangles the ray hits under ``rule``
("owned", the default, or "closed"), the one with the smallest exact t, ties to the smallest index, found
through the mesh's BVH (the answer is the brute-force one): ``MeshHit(triangle, t, location, barycentric)``
as ``intersect`` gives them. Releases the GIL for meshes.

Sphere set (``scene`` a ``raykernel.SphereSet``; docs/contract.md §8, §10): the sphere with the smallest root in
the interval (the tangent root included), an exact tie to the smaller index: ``SphereHit(sphere, t)``.

Every scene takes an interval, ``t_min`` ≤ t ≤ ``t_max``, closed, compared exactly (docs/contract.md §8: the
exact t against the doubles, never a rounded t). Raises ``ValueError`` naming the invalid ray, interval, plane or
sphere.)doc");

  m.def(
      "nearest_hit_exact",
      [](shown::RayLike ray, shown::Scene scene, shown::OptionalRule rule, double t_min,
         double t_max) -> shown::NearestHit { return nearest_in_scene(ray, scene, rule, t_min, t_max, true); },
      py::arg("ray"), py::arg("scene"), py::kw_only(), py::arg("rule") = py::none(), py::arg("t_min") = 0.0,
      py::arg("t_max") = inf,
      R"doc(The reference nearest hit, in exact rationals, by brute force (every plane or every triangle, no
BVH): the same answer as ``nearest_hit``. Releases the GIL.)doc");

  m.def(
      "nearest_hit_naive",
      [](shown::RayLike ray, shown::Scene scene, double t_min, double t_max) -> shown::NearestHit {
        if (py::isinstance<PythonMesh>(scene))
          return nearest_hit_mesh(ray, scene.cast<const PythonMesh&>(), t_min, t_max, py::none(), Path::naive);
        if (is_sphere_set(scene)) throw py::type_error("scene: nearest_hit_naive has no form for a SphereSet");
        require_whole_ray(py::float_(t_min), py::float_(t_max), "the naive loop over planes");
        return nearest(ray, scene,
                       [](const Ray& r, const raykernel::PlaneSet& p) { return nearest_hit_naive(r, p.planes()); });
      },
      py::arg("ray"), py::arg("scene"), py::kw_only(), py::arg("t_min") = 0.0, py::arg("t_max") = inf,
      R"doc(The textbook loop in plain doubles, the baseline: no guarantee.

Planes: ``intersect_naive`` per plane, the smallest rounded t wins (ties to the smallest index); no validation.
Mesh: Möller–Trumbore in doubles (``intersect_naive``) on the triangles of the leaves the mesh's BVH returns,
the smallest computed t wins (ties to the smallest index); ``ValueError`` for an invalid ray. Releases the GIL
for meshes.)doc");
}

}  // namespace raykernel::python
