// PlaneSet: the planes of a scene, read from Python and prepared once (raykernel::PlaneSet: validated once,
// planes coinciding with earlier ones set aside once), for nearest_hit and its vectorized form.
#pragma once

#include "convert.hpp"

#include <raykernel/nearest_hit.hpp>
#include <raykernel/raykernel.hpp>

#include <optional>
#include <span>
#include <vector>

namespace raykernel::python {

class PlaneSet {
 public:
  // From a sequence of planes ((point, normal) pairs), or from `points` and `normals` as (m, 3) arrays.
  // Throws InvalidInput naming the first invalid plane ("plane 3: plane normal is the zero vector").
  PlaneSet(py::handle planes_or_points, py::handle normals);

  [[nodiscard]] std::span<const Plane> planes() const noexcept { return prepared_.planes(); }
  [[nodiscard]] const raykernel::PlaneSet& prepared() const noexcept { return prepared_; }

 private:
  raykernel::PlaneSet prepared_;
};

// The prepared planes of a PlaneSet, or of any sequence of planes (prepared into `storage` for the call).
// Throws InvalidInput naming the first invalid plane.
[[nodiscard]] const raykernel::PlaneSet& planes_from(py::handle value, std::optional<raykernel::PlaneSet>& storage);

}  // namespace raykernel::python
