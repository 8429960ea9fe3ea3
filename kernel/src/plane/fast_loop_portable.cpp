// The batch fast loop for any target, one query at a time (plane/fast_loop.hpp).
#include "plane/fast_loop.hpp"
#include "core/fp_requirements.hpp"

RAYKERNEL_DEFINE_FAST_LOOPS(portable, double)
