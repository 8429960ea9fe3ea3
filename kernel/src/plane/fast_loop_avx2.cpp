// The batch fast loop compiled for AVX2 with FMA (plane/fast_loop.hpp; -march=x86-64-v3 in kernel/CMakeLists.txt).
#include "plane/fast_loop.hpp"
#include "core/fp_requirements.hpp"

RAYKERNEL_DEFINE_FAST_LOOPS(avx2, detail::Lanes4)
