// PlaneSet and the scalar nearest hit (docs/contract.md §4): the first plane one ray meets.
#include "bindings.hpp"
#include "convert.hpp"
#include "plane_set.hpp"

#include <raykernel/nearest_hit.hpp>

#include <optional>
#include <string>

namespace raykernel::python {
namespace {

// Below this many planes a nearest hit takes well under a microsecond: not worth releasing the GIL.
constexpr std::size_t release_gil_above_planes = 64;

void validate_planes(std::span<const Plane> planes) {
  for (std::size_t k = 0; k < planes.size(); ++k)
    if (const std::optional<std::string> reason = validate(planes[k]))
      throw invalid_input("plane " + std::to_string(k) + ": " + *reason);
}

template <class F>
py::object nearest(py::handle ray, py::handle planes, F&& search) {
  const Ray r = ray_from(ray);
  std::vector<Plane> storage;
  const std::span<const Plane> set = planes_from(planes, storage);
  std::optional<NearestHit> hit;
  if (set.size() > release_gil_above_planes) {
    py::gil_scoped_release release;
    hit = search(r, set);
  } else {
    hit = search(r, set);
  }
  return to_python(hit);
}

}  // namespace

PlaneSet::PlaneSet(py::handle planes_or_points, py::handle normals) {
  if (normals.is_none()) {
    const py::sequence seq = py::reinterpret_borrow<py::sequence>(planes_or_points);
    if (!PySequence_Check(planes_or_points.ptr()))
      throw py::type_error("planes: expected a sequence of (point, normal) pairs");
    const std::size_t m = py::len(planes_or_points);
    planes_.reserve(m);
    for (std::size_t k = 0; k < m; ++k) planes_.push_back(plane_from(seq[k], "plane " + std::to_string(k)));
  } else {
    ColumnsView points(planes_or_points, "points"), ns(normals, "normals");
    require_rows(ns, "normals", points.rows(), "points");
    planes_.reserve(points.rows());
    for (std::size_t k = 0; k < points.rows(); ++k) planes_.push_back({points.row(k), ns.row(k)});
  }
  validate_planes(planes_);
}

std::span<const Plane> planes_from(py::handle value, std::vector<Plane>& storage) {
  if (py::isinstance<PlaneSet>(value)) return value.cast<const PlaneSet&>().planes();
  if (!PySequence_Check(value.ptr()) || PyUnicode_Check(value.ptr()))
    throw py::type_error("planes: expected a raykernel.PlaneSet or a sequence of (point, normal) pairs, got " +
                         std::string(Py_TYPE(value.ptr())->tp_name));
  const std::size_t m = py::len(value);
  storage.clear();
  storage.reserve(m);
  const py::sequence seq = py::reinterpret_borrow<py::sequence>(value);
  for (std::size_t k = 0; k < m; ++k) storage.push_back(plane_from(seq[k], "plane " + std::to_string(k)));
  return storage;
}

void bind_nearest(py::module_& m) {
  py::class_<PlaneSet>(m, "PlaneSet", R"doc(The planes of a scene, read and validated once.

``PlaneSet(planes)`` takes a sequence of ``(point, normal)`` pairs (e.g. ``raykernel.Plane`` values);
``PlaneSet(points, normals)`` takes two (m, 3) float64 arrays. Plane k is the k-th, counted from 0: the index
``nearest_hit`` answers. Raises ``ValueError`` naming the first invalid plane
(``"plane 3: plane normal is the zero vector"``). Pass it to ``nearest_hit`` and ``nearest_hit_batch``
instead of a list to read and validate the planes once.)doc")
      .def(py::init([](py::handle planes, py::handle normals) { return PlaneSet(planes, normals); }), py::arg("planes"),
           py::arg("normals") = py::none())
      .def("__len__", [](const PlaneSet& s) { return s.planes().size(); })
      .def(
          "__getitem__",
          [](const PlaneSet& s, py::ssize_t k) {
            const auto m = static_cast<py::ssize_t>(s.planes().size());
            if (k < 0) k += m;
            if (k < 0 || k >= m) throw py::index_error("plane index out of range");
            return to_python(s.planes()[static_cast<std::size_t>(k)]);
          },
          py::arg("index"))
      .def_property_readonly(
          "points",
          [](const PlaneSet& s) {
            py::array_t<double> a({static_cast<py::ssize_t>(s.planes().size()), py::ssize_t{3}});
            auto w = a.mutable_unchecked<2>();
            for (std::size_t k = 0; k < s.planes().size(); ++k) {
              const Vec3& p = s.planes()[k].point;
              const auto i = static_cast<py::ssize_t>(k);
              w(i, 0) = p.x, w(i, 1) = p.y, w(i, 2) = p.z;
            }
            return a;
          },
          "The planes' points, a new (m, 3) array.")
      .def_property_readonly(
          "normals",
          [](const PlaneSet& s) {
            py::array_t<double> a({static_cast<py::ssize_t>(s.planes().size()), py::ssize_t{3}});
            auto w = a.mutable_unchecked<2>();
            for (std::size_t k = 0; k < s.planes().size(); ++k) {
              const Vec3& n = s.planes()[k].normal;
              const auto i = static_cast<py::ssize_t>(k);
              w(i, 0) = n.x, w(i, 1) = n.y, w(i, 2) = n.z;
            }
            return a;
          },
          "The planes' normals, a new (m, 3) array.")
      .def("__repr__", [](const PlaneSet& s) { return "PlaneSet(" + std::to_string(s.planes().size()) + " planes)"; });

  m.def(
      "nearest_hit",
      [](py::handle ray, py::handle planes) {
        return nearest(ray, planes, [](const Ray& r, std::span<const Plane> p) { return nearest_hit(r, p); });
      },
      py::arg("ray"), py::arg("planes"),
      R"doc(The first plane ``ray`` meets, decided exactly: ``NearestHit(plane, t)`` or None.

Among the planes whose relation is HIT (t ≥ 0), the one with the smallest exact t = num/den; ties go to the
smallest index; ``t`` is that plane's t rounded as ``intersect`` rounds it. t values are compared exactly,
never after rounding, so planes closer than an ulp are ordered right (docs/contract.md §4). ``planes`` is a
``PlaneSet`` or a sequence of ``(point, normal)`` pairs. Raises ``ValueError`` naming the invalid ray or
plane.)doc");

  m.def(
      "nearest_hit_exact",
      [](py::handle ray, py::handle planes) {
        const Ray r = ray_from(ray);
        std::vector<Plane> storage;
        const std::span<const Plane> set = planes_from(planes, storage);
        std::optional<NearestHit> hit;
        {
          py::gil_scoped_release release;
          hit = nearest_hit_exact(r, set);
        }
        return to_python(hit);
      },
      py::arg("ray"), py::arg("planes"),
      "The reference nearest hit, in exact rationals: the same answer as ``nearest_hit``. Releases the GIL.");

  m.def(
      "nearest_hit_naive",
      [](py::handle ray, py::handle planes) {
        return nearest(ray, planes, [](const Ray& r, std::span<const Plane> p) { return nearest_hit_naive(r, p); });
      },
      py::arg("ray"), py::arg("planes"),
      R"doc(The textbook loop in plain doubles: ``intersect_naive`` per plane, the smallest rounded t wins
(ties to the smallest index). No validation and no guarantee: the baseline.)doc");
}

}  // namespace raykernel::python
