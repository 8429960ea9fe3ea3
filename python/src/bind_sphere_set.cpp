// raykernel.SphereSet and the sphere forms of the scene queries (sphere_set.hpp; docs/contract.md §8 and §10).
#include "sphere_set.hpp"

#include "batch_support.hpp"
#include "bindings.hpp"
#include "ray_batch.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace raykernel::python {
namespace {

py::object to_python(const std::optional<SphereHit>& hit) {
  if (!hit) return py::none();
  return types().sphere_hit(hit->sphere, hit->t);
}

std::optional<SphereHit> nearest_on(const Ray& ray, const RayInterval& interval, const raykernel::SphereSet& spheres,
                                    bool exact) {
  return exact ? nearest_hit_exact(ray, interval, spheres.spheres()) : nearest_hit(ray, interval, spheres);
}

// From an (m, 3) array of centres and an (m,) array of radii, or from a sequence of raykernel.Sphere.
std::vector<Sphere> read_spheres(py::handle centers_or_spheres, py::handle radii) {
  std::vector<Sphere> spheres;
  if (radii.is_none()) {
    if (!PySequence_Check(centers_or_spheres.ptr()) || py::isinstance<py::array>(centers_or_spheres))
      throw py::type_error("SphereSet: give centers (an (m, 3) array) with radii (an (m,) array), or a sequence of "
                           "raykernel.Sphere");
    const py::sequence all = py::reinterpret_borrow<py::sequence>(centers_or_spheres);
    for (std::size_t k = 0; k < py::len(all); ++k)
      spheres.push_back(sphere_from(all[k], "sphere " + std::to_string(k)));
    return spheres;
  }
  const ColumnsView c(centers_or_spheres, "centers");
  const ValuesView r(radii, "radii");
  require_rows(r, "radii", c.rows(), "centers");
  for (std::size_t k = 0; k < c.rows(); ++k) spheres.push_back({c.row(k), r.value(k)});
  return spheres;
}

}  // namespace

py::object nearest_hit_spheres(py::handle ray, const raykernel::SphereSet& spheres, double t_min, double t_max,
                               bool exact) {
  const Ray r = ray_from(ray);
  const RayInterval interval{t_min, t_max};
  std::optional<SphereHit> hit;
  {
    py::gil_scoped_release release;
    hit = nearest_on(r, interval, spheres, exact);
  }
  return to_python(hit);
}

py::object nearest_hit_spheres_batch(py::handle origins, py::handle directions, const raykernel::SphereSet& spheres,
                                     py::handle t_min, py::handle t_max, const std::string& path,
                                     const std::string& errors, std::optional<unsigned> threads) {
  const RayRows b(origins, directions, t_min, t_max, py::none(), path, errors);
  const NearestColumns c = nearest_columns(b, threads, b.exact ? 4 : 256, [&](const Ray& ray, const RayInterval& i) {
    return nearest_on(ray, i, spheres, b.exact);
  });
  return types().sphere_hit_arrays(c.index, c.t, c.valid);
}

bool occluded_spheres(const Ray& ray, const RayInterval& interval, const raykernel::SphereSet& spheres, bool exact) {
  return exact ? nearest_hit_exact(ray, interval, spheres.spheres()).has_value() : occluded(ray, interval, spheres);
}

bool occluded_segment_spheres(const Vec3& p, const Vec3& q, const raykernel::SphereSet& spheres, bool exact) {
  if (!exact) return occluded(p, q, spheres);
  const auto all = spheres.spheres();
  return std::any_of(all.begin(), all.end(), [&](const Sphere& s) { return segment_meets_exact(p, q, s); });
}

void bind_sphere_set(py::module_& m) {
  py::class_<raykernel::SphereSet>(m, "SphereSet", R"doc(The spheres of a scene, read and validated once.

``SphereSet(centers, radii)``: an (m, 3) array of centres and an (m,) array of radii (real numbers, read as
float64), or ``SphereSet(spheres)``: a sequence of ``raykernel.Sphere``. Raises ``ValueError`` naming the first
invalid sphere ("sphere 3: sphere radius is not positive"). From eight spheres on, a bounding volume hierarchy over
their boxes (each rounded outwards, so it holds its sphere exactly) is built once, and the queries walk it nearest
first. Pass it as the ``scene`` of ``nearest_hit``, ``nearest_hit_exact``, ``nearest_hit_batch``, ``occluded``,
``occluded_segment``, ``occluded_batch`` and ``occluded_segment_batch`` (docs/contract.md §8 and §10: a sphere is
closed; it blocks a ray when a root, the tangent root included, lies in the ray's interval, compared exactly).
Pickles (as its centres and radii).)doc")
      .def(py::init([](shown::SpheresLike centers, shown::OptionalArrayLike radii) {
             std::vector<Sphere> spheres = read_spheres(centers, radii);
             py::gil_scoped_release release;
             return raykernel::SphereSet(spheres);
           }),
           py::arg("centers"), py::arg("radii") = py::none())
      .def("__len__", [](const raykernel::SphereSet& s) { return s.size(); })
      .def(
          "__getitem__",
          [](const raykernel::SphereSet& s, py::ssize_t k) -> shown::Sphere {
            const auto m = static_cast<py::ssize_t>(s.size());
            if (k < 0) k += m;
            if (k < 0 || k >= m) throw py::index_error("sphere index out of range");
            return python::to_python(s.spheres()[static_cast<std::size_t>(k)]);
          },
          py::arg("index"))
      .def_property_readonly(
          "centers",
          [](const raykernel::SphereSet& s) {
            py::array_t<double> a({static_cast<py::ssize_t>(s.size()), py::ssize_t{3}});
            auto w = a.mutable_unchecked<2>();
            for (std::size_t k = 0; k < s.size(); ++k) {
              const Vec3& c = s.spheres()[k].center;
              const auto i = static_cast<py::ssize_t>(k);
              w(i, 0) = c.x, w(i, 1) = c.y, w(i, 2) = c.z;
            }
            return a;
          },
          "The centres, a new (m, 3) array.")
      .def_property_readonly(
          "radii",
          [](const raykernel::SphereSet& s) {
            py::array_t<double> a(static_cast<py::ssize_t>(s.size()));
            for (std::size_t k = 0; k < s.size(); ++k)
              a.mutable_at(static_cast<py::ssize_t>(k)) = s.spheres()[k].radius;
            return a;
          },
          "The radii, a new (m,) array.")
      .def(py::pickle([](py::handle self) { return py::make_tuple(self.attr("centers"), self.attr("radii")); },
                      [](const py::tuple& state) {
                        if (state.size() != 2) throw py::value_error("SphereSet: a pickled state is (centers, radii)");
                        return raykernel::SphereSet(read_spheres(state[0], state[1]));
                      }))
      .def("__repr__", [](const raykernel::SphereSet& s) {
        return "SphereSet(" + std::to_string(s.size()) + (s.size() == 1 ? " sphere)" : " spheres)");
      });
}

}  // namespace raykernel::python
