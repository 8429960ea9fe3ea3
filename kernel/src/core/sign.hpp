// The answer of a sign predicate stage: a certified sign, or `uncertain` when the stage's error bound
// cannot decide (a stage never guesses).
#pragma once

#include "core/lanes.hpp"

#include <cstdint>
#include <type_traits>

namespace raykernel::detail {

enum class Sign : std::int8_t { negative = -1, zero = 0, positive = 1, uncertain = 2 };

[[nodiscard]] constexpr bool is_certain(Sign s) noexcept { return s != Sign::uncertain; }

// The Sign of an exact integer sign (−1, 0, +1, or any int by its sign).
[[nodiscard]] constexpr Sign sign_from_int(int s) noexcept {
  return s < 0 ? Sign::negative : (s > 0 ? Sign::positive : Sign::zero);
}

// A filter's int answer (+1, −1, or 0 for uncertain: a filter never certifies zero) as a Sign.
[[nodiscard]] constexpr Sign sign_or_uncertain(int filter) noexcept {
  return filter > 0 ? Sign::positive : (filter < 0 ? Sign::negative : Sign::uncertain);
}

// Signs as integer lanes, for the routines written for both double and Lanes8: the values of Sign
// (+1, −1, 0, and 2 for uncertain) in a std::int64_t, or in each lane of a Mask8.
inline constexpr std::int64_t uncertain_lane = static_cast<std::int64_t>(Sign::uncertain);

// +1 where `above`, −1 where `below`, uncertain where neither; no branch.
[[nodiscard]] [[gnu::always_inline]] inline std::int64_t sign_lanes(bool above, bool below) noexcept {
  const std::int64_t s = static_cast<std::int64_t>(above) - static_cast<std::int64_t>(below);
  return s + 2 * static_cast<std::int64_t>(s == 0);
}
// The same per lane of a vector (masks are −1 where true).
template <class Mask>
  requires std::is_same_v<Mask, Mask2> || std::is_same_v<Mask, Mask4> || std::is_same_v<Mask, Mask8>
[[nodiscard]] [[gnu::always_inline]] inline Mask sign_lanes(Mask above, Mask below) noexcept {
  const Mask s = below - above;
  return s - 2 * (s == 0);
}

// `first` where it is certain, else `second`.
template <class I>
[[nodiscard]] [[gnu::always_inline]] inline I first_certain_lanes(I first, I second) noexcept {
  return select(first == uncertain_lane, second, first);
}

}  // namespace raykernel::detail
