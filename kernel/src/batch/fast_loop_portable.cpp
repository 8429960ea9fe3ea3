// The batch fast loop for any target, one query at a time (batch/fast_loop.hpp).
#include "batch/fast_loop.hpp"
#include "certified/fp_requirements.hpp"

RAYKERNEL_DEFINE_FAST_LOOPS(portable, double)
