// The one escalation policy of every certified predicate (what CGAL's Filtered_predicate writes once for its
// kernels): a sign is asked of its stages, cheapest first, each stage only when every stage before it left the
// sign uncertain; the first certain answer is the answer. A query that decides several signs (a plane's num and
// den, a triangle's three π, den and num, an orientation, the order of two hits) escalates each sign on its
// own, and keeps one trace for all of them: the latest stage any of its signs was asked of (Stage's order:
// filter, compensated, expansion, exact), which is what `*_traced` reports and the benchmarks count.
//
// A stage is a SignStage: the Stage it counts as and a callable returning Sign (certain, or `uncertain` to
// pass on). Several steps may count as one Stage (the plane's two compensated levels; the comparison's
// shortcut without arithmetic counts as the filter). The exact stage, which allocates and may throw, is the
// caller's: `sign` returns `uncertain` when no stage certified, and the caller then asks its exact stage and
// records it with `reach(Stage::exact)` (or `exact_sign`, which does both). So `sign` itself is noexcept
// whenever its stages are, and runs inside the multiversioned functions (core/multiversion.hpp).
//
// Used by: plane/ray_plane_cascade.cpp (certified_signs), triangle/ray_triangle_cascade.cpp (TriangleCascade),
// nearest/triangle_candidate.hpp (a triangle candidate's signs), nearest/nearest_candidates.hpp
// (compare_candidates_certified), orient/orient_predicates.hpp (orient2d_sign, orient3d_sign),
// spawn/spawn_certified.cpp (σ and s).
//
// Certified by:
//   proofs/core/Escalation.v, `escalate_sound`: a certain answer is the answer of a stage that was asked (so the
//     exact sign when every stage is sound);
//   proofs/core/Escalation.v, `escalate_first_certain`: it is the first certain answer, and no later stage is asked;
//   proofs/core/Escalation.v, `escalate_trace`: the trace is the latest stage asked, never lower than before;
//   proofs/core/Escalation.v, `exact_sign_reaches_exact`: exact_sign reaches the exact stage exactly when no stage
//     certified.
//   The control flow is twinned there and run against this template by the differential runner (routine
//   escalate: random lists of stage answers; the answer, the number of stages asked and the trace compared).
#pragma once

#include "core/sign.hpp"

#include <raykernel/core.hpp>

namespace raykernel::detail {

// One stage of a sign: the Stage it counts as, and its decision.
template <class Decide>
struct SignStage {
  Stage stage;
  Decide decide;
};
template <class Decide>
SignStage(Stage, Decide) -> SignStage<Decide>;

// The trace of one query's escalations: the latest stage asked of any of its signs.
class Escalation {
 public:
  constexpr Escalation() noexcept = default;
  constexpr explicit Escalation(Stage start) noexcept : reached_(start) {}

  // The answer of the first of `stages` that certifies one, each asked only while the answers before it are
  // uncertain; `uncertain` when none certifies (the caller's exact stage decides then).
  template <class... Decide>
  [[gnu::always_inline]] constexpr Sign sign(SignStage<Decide>... stages) {
    Sign s = Sign::uncertain;
    static_cast<void>(((reach(stages.stage), s = stages.decide(), is_certain(s)) || ...));
    return s;
  }

  // `sign`, then the exact stage when no stage certified: `exact()` returns the exact sign as an int (−1, 0, +1).
  template <class Exact, class... Decide>
  [[gnu::always_inline]] int exact_sign(Exact exact, SignStage<Decide>... stages) {
    const Sign s = sign(stages...);
    if (is_certain(s)) return static_cast<int>(s);
    reach(Stage::exact);
    return exact();
  }

  // Records that a stage was asked (for the steps that are not signs: a tie-break, the exact stage).
  constexpr void reach(Stage stage) noexcept {
    if (static_cast<int>(stage) > static_cast<int>(reached_)) reached_ = stage;
  }
  [[nodiscard]] constexpr Stage reached() const noexcept { return reached_; }

 private:
  Stage reached_ = Stage::filter;
};

}  // namespace raykernel::detail
