// The nearest-hit module's rare paths, compiled apart and multiversioned (core/multiversion.hpp: FMA where the CPU
// has it), so that the search's hot loop stays small: a triangle's t beyond stage 2.
#include "core/multiversion.hpp"
#include "nearest/triangle_candidate.hpp"

namespace raykernel::detail {

// RN(t) of a triangle candidate whose stage-2 rounding was not certain (`candidate` its rounded value): round_quotient
// on stage 3's tail enclosures (den's, or stage 2's when den's expansion is too long), then the rounding
// boundaries of the candidate in expansions (core/quotient_boundary.hpp), then the exact stage. As the
// triangle cascade rounds (triangle/ray_triangle_cascade.cpp), with the boundaries before rationals.
RAYKERNEL_MULTIVERSION
void round_triangle_t_beyond_stage2(TriangleCandidate& c, double candidate) noexcept {
  c.t_stage = Stage::expansion;
  c.stage3();
  if (const std::optional<Enclosure>& n = c.num3_tail_) {
    const std::optional<Enclosure>& d = c.den3_tail_;
    const QuotientRounding r = round_quotient(*n, prepare_divisor(d ? *d : c.den_compensated()));
    if (r.certain) {
      c.t = r.t;
      return;
    }
    candidate = r.t;
  }
  if (c.short_.exact) {
    if (const std::optional<double> q =
            round_quotient_at_boundaries(c.short_.num, c.short_.den, static_cast<int>(c.den_sign), candidate)) {
      c.t = *q;
      return;
    }
  }
  c.t_stage = Stage::exact;
  c.t = exact::round_triangle_quotients(*c.ray_, *c.source, true, false).t;
}

}  // namespace raykernel::detail
