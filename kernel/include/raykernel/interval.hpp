// raykernel/interval.hpp: the interval [t_min, t_max] a ray may carry (docs/contract.md §8), and its validation.
// The queries that take one are in <raykernel/occlusion.hpp>.
//
// This header needs neither CGAL nor GMP.
#pragma once

#include <limits>
#include <optional>
#include <string>

namespace raykernel {

// The interval [t_min, t_max] of a ray (closed at both ends). Valid when 0 ≤ t_min ≤ t_max ≤ +inf, t_min finite,
// neither NaN (t_min = −0 is 0). The default is the whole ray, [0, +inf].
struct RayInterval {
  double t_min = 0;
  double t_max = std::numeric_limits<double>::infinity();
};

// Why `interval` is not valid, naming the bound ("t_min is NaN", "t_min is negative", "t_min is +inf",
// "t_max is NaN", "t_min is greater than t_max"), or nothing. Decided from the doubles' bits: the same answer in
// any floating-point environment.
[[nodiscard]] std::optional<std::string> validate(const RayInterval& interval);

}  // namespace raykernel
