// raykernel._raykernel: the compiled half of the Python package `raykernel` (python/raykernel/__init__.py
// re-exports it with the pure-Python types of raykernel/_types.py).
#include "bindings.hpp"
#include "convert.hpp"

#include <raykernel/raykernel.hpp>

#include <string>

PYBIND11_MODULE(_raykernel, m) {
  namespace py = pybind11;
  using namespace raykernel::python;
  m.doc() = "raykernel's C++ kernel (pybind11). Use it through the package `raykernel`.";
  load_types();

  // invalid_input derives from std::invalid_argument: Python sees a ValueError subclass whose message names
  // the field ("ray direction is the zero vector").
  py::register_exception<raykernel::invalid_input>(m, "InvalidInput", PyExc_ValueError)
      .attr("__doc__") = "Input that has no answer: a NaN or infinite component, a zero direction or normal, a sphere "
                         "radius that is not positive.\n\n"
                         "A ValueError whose message names the field, and for arrays the row: \"query 17: ray "
                         "direction is the zero vector\".";

  bind_ray_plane(m);
  bind_nearest(m);
  bind_batch(m);
  bind_triangle(m);
  bind_sphere(m);
  bind_sphere_set(m);
  bind_mesh(m);
  bind_occlusion(m);
  bind_closest(m);
  bind_spawn(m);
  bind_testkit(m);
  bind_cli(m);

  m.attr("__version__") = std::string(raykernel::version());
}
