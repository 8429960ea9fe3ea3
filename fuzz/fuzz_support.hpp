// What every raykernel fuzz harness shares: failure reports that say how to reproduce, and the per-stage
// statistics that show how deep into the certified cascade the fuzzer's executions reach.
//
// A harness calls `check(condition, what)` for every property; a failed check prints the property, the
// harness's description of the input and the replay command, then aborts (libFuzzer then saves the input
// as crash-<sha1>; the replay program's ctest fails). Statistics are printed at exit when the environment
// variable RAYKERNEL_FUZZ_STATS is set to anything but 0 (fuzz/ci-run-fuzzers.sh sets it).
#pragma once

#include <raykernel/raykernel.hpp>

#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace raykernel::fuzz {

// The harness's name and a description of the input under test, printed by a failed check.
void set_harness_name(std::string_view name);
void set_input_describer(std::function<std::string()> describe);
// The file the replay program is running (empty under libFuzzer).
void set_current_input_file(std::string path);

// Aborts with a report unless `condition` holds. `what` is a string, or a callable returning one that is
// only called on failure (so that messages cost nothing on the hot path).
[[noreturn]] void fail(std::string_view what);
template <class What>
inline void check(bool condition, What&& what) {
  if (condition) [[likely]]
    return;
  if constexpr (std::is_invocable_v<What>) {
    fail(std::string(what()));
  } else {
    fail(std::string_view(what));
  }
}

// A double as C99 hex ("0x1.8p+1", "-0x0p+0", "inf", "nan"), exact and readable by strtod.
[[nodiscard]] std::string hex(double x);
// The 64-bit pattern of a double, as 16 hex digits.
[[nodiscard]] std::string bits_of(double x);

// ---------------------------------------------------------------------------------------------------------
// docs/contract.md §1's invalid input, decided from the bit patterns alone (no floating-point comparison), so that a
// harness's idea of validity shares nothing with the kernel's.

[[nodiscard]] inline std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
[[nodiscard]] inline bool finite_by_bits(double x) { return ((bits(x) >> 52) & 0x7ff) != 0x7ff; }
[[nodiscard]] inline bool zero_by_bits(double x) { return (bits(x) << 1) == 0; }  // +0 or -0
[[nodiscard]] inline bool finite_vector_by_bits(const Vec3& v) {
  return finite_by_bits(v.x) && finite_by_bits(v.y) && finite_by_bits(v.z);
}
[[nodiscard]] inline bool zero_vector_by_bits(const Vec3& v) {
  return zero_by_bits(v.x) && zero_by_bits(v.y) && zero_by_bits(v.z);
}
// A non-finite component, or a zero direction.
[[nodiscard]] inline bool ray_invalid_by_bits(const Ray& r) {
  return !finite_vector_by_bits(r.origin) || !finite_vector_by_bits(r.direction) || zero_vector_by_bits(r.direction);
}
// A non-finite component, or a zero normal.
[[nodiscard]] inline bool plane_invalid_by_bits(const Plane& p) {
  return !finite_vector_by_bits(p.point) || !finite_vector_by_bits(p.normal) || zero_vector_by_bits(p.normal);
}

// ---------------------------------------------------------------------------------------------------------
// Statistics.

[[nodiscard]] bool stats_requested();

// How the executions of one group of inputs (say, one decoder mode) went through the certified cascade.
struct StageCounts {
  std::uint64_t executions = 0;
  std::uint64_t invalid = 0;                // rejected input (never reaches a stage)
  std::array<std::uint64_t, 4> relation{};  // by Relation, valid input only
  std::array<std::uint64_t, 4> relation_stage{};
  std::array<std::uint64_t, 4> t_stage{};  // hit and behind only (an exact t = 0 comes with the relation)
  std::array<std::uint64_t, 4> deepest{};  // max(relation_stage, t_stage): the slowest stage the query needed

  void add_invalid() {
    ++executions;
    ++invalid;
  }
  void add(const TracedIntersection& traced);
  StageCounts& operator+=(const StageCounts& other);
};

// "%6.2f" of 100·part/whole, or "     -" when whole is 0; and the four percentages of a count array's sum,
// each preceded by a space: the cells of the stats tables.
[[nodiscard]] std::string percent_text(std::uint64_t part, std::uint64_t whole);
[[nodiscard]] std::string shares_text(const std::array<std::uint64_t, 4>& counts);

// A table: one row per named group, and a total row.
[[nodiscard]] std::string format_stage_table(std::string_view title,
                                             const std::vector<std::pair<std::string, StageCounts>>& rows);

// Calls `print` at exit (once), when stats_requested().
void print_at_exit(std::function<void()> print);

}  // namespace raykernel::fuzz
