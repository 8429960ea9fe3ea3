// The parts of the extension module raykernel._raykernel, one function per group of bindings (module.cpp
// calls them in order). Adding a primitive adds a bind_* function and its .cpp; the docstrings live beside
// the bindings, and raykernel/_raykernel.pyi states the same signatures for type checkers.
#pragma once

#include <pybind11/pybind11.h>

namespace raykernel::python {

void bind_ray_plane(pybind11::module_& m);  // scalar ray–plane queries (docs/contract.md §1)
void bind_nearest(pybind11::module_& m);    // PlaneSet and the scalar nearest hit (docs/contract.md §4)
void bind_batch(pybind11::module_& m);      // the vectorized forms over NumPy arrays
void bind_testkit(pybind11::module_& m);    // raykernel::testkit: hard queries, reference check, fuzz decoder

}  // namespace raykernel::python
