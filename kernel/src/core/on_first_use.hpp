// Values computed on first use, by index: a query's stage results per determinant or per leaf vector
// (triangle/ray_triangle_cascade.cpp's expansions, triangle/ray_triangle_stages.hpp's integer leaves). Not
// std::optional: GCC zeroes an optional's payload when it constructs it (7.8 KB per query for the expansions);
// here a value's storage is left uninitialized until it is computed.
#pragma once

#include <array>
#include <cstddef>

namespace raykernel::detail {

template <class T, std::size_t N>
class OnFirstUse {
 public:
  // Value k, computed by `compute()` the first time it is asked.
  template <class Compute>
  [[gnu::always_inline]] const T& get(std::size_t k, Compute compute) {
    if (!computed_[k]) {
      value_[k] = compute();
      computed_[k] = true;
    }
    return value_[k];
  }

 private:
  std::array<T, N> value_;
  std::array<bool, N> computed_{};
};

}  // namespace raykernel::detail
