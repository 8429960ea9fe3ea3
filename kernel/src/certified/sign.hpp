// The answer of a sign predicate stage: a certified sign, or `uncertain` when the stage's error bound
// cannot decide (a stage never guesses).
#pragma once

#include <cstdint>

namespace raykernel::detail {

enum class Sign : std::int8_t { negative = -1, zero = 0, positive = 1, uncertain = 2 };

[[nodiscard]] constexpr bool is_certain(Sign s) noexcept { return s != Sign::uncertain; }

[[nodiscard]] constexpr Sign negate(Sign s) noexcept {
  switch (s) {
    case Sign::negative: return Sign::positive;
    case Sign::positive: return Sign::negative;
    default: return s;
  }
}

}  // namespace raykernel::detail
