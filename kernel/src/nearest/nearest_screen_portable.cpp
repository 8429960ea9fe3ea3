// The nearest_hit screen for any target (nearest/nearest_screen.hpp): two planes at a time (one SSE2
// register on x86-64; the vector extensions lower to scalar operations elsewhere).
#include "core/fp_requirements.hpp"
#include "nearest/nearest_screen.hpp"

RAYKERNEL_DEFINE_NEAREST_SCREEN(portable, detail::Lanes2)
