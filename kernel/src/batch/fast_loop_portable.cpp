// The batch fast loop compiled for portable (batch/fast_loop.hpp; the flags are set in kernel/CMakeLists.txt).
#include "batch/fast_loop.hpp"

RAYKERNEL_DEFINE_FAST_LOOPS(portable)
