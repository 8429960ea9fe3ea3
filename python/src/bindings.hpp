// The parts of the extension module raykernel._raykernel, one function per group of bindings (module.cpp
// calls them in order). Adding a primitive adds a bind_* function and its .cpp; the docstrings live beside
// the bindings, and raykernel/_raykernel.pyi states the same signatures for type checkers.
#pragma once

#include <pybind11/pybind11.h>

namespace raykernel::python {

void bind_ray_plane(pybind11::module_& m);  // scalar ray–plane, ray–triangle and ray–sphere queries (§1, §6, §10)
void bind_nearest(pybind11::module_& m);    // PlaneSet and the scalar nearest hit (docs/contract.md §4)
void bind_batch(pybind11::module_& m);      // the vectorized ray–plane forms over NumPy arrays
void bind_triangle(pybind11::module_& m);   // the vectorized ray–triangle forms (docs/contract.md §6)
void bind_sphere(pybind11::module_& m);     // the vectorized ray–sphere form (docs/contract.md §10)
void bind_sphere_set(pybind11::module_& m);  // SphereSet: spheres as a scene (docs/contract.md §8, §10)
void bind_mesh(pybind11::module_& m);       // Mesh, load_mesh, the mesh nearest hit (docs/contract.md §7)
void bind_occlusion(pybind11::module_& m);   // all hits, crossings, occluded over arrays (docs/contract.md §8)
void bind_closest(pybind11::module_& m);     // the exact closest point of a mesh (docs/contract.md §11)
void bind_spawn(pybind11::module_& m);      // spawn and spawn_to: secondary rays (docs/contract.md §9)
void bind_testkit(pybind11::module_& m);
void bind_cli(pybind11::module_& m);         // _cli_main: the command-line tool (when built with the CLI)    // raykernel::testkit: hard queries, reference check, fuzz decoder

}  // namespace raykernel::python
