// PlaneSet: the planes of a scene, read from Python and validated once, for nearest_hit and its vectorized
// form. It is the Python home of a prepared plane set: when the kernel gains one (issue 13: validated once,
// duplicates found once), PlaneSet holds it and nothing in the Python API changes.
#pragma once

#include "convert.hpp"

#include <raykernel/raykernel.hpp>

#include <span>
#include <vector>

namespace raykernel::python {

class PlaneSet {
 public:
  // From a sequence of planes ((point, normal) pairs), or from `points` and `normals` as (m, 3) arrays.
  // Throws InvalidInput naming the first invalid plane ("plane 3: plane normal is the zero vector").
  PlaneSet(py::handle planes_or_points, py::handle normals);

  [[nodiscard]] std::span<const Plane> planes() const noexcept { return planes_; }

 private:
  std::vector<Plane> planes_;
};

// The planes of a PlaneSet, or of any sequence of planes (read into `storage`).
[[nodiscard]] std::span<const Plane> planes_from(py::handle value, std::vector<Plane>& storage);

}  // namespace raykernel::python
