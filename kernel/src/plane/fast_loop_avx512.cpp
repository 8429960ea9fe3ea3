// The batch fast loop compiled for AVX-512 (plane/fast_loop.hpp; -march=x86-64-v4 in kernel/CMakeLists.txt).
#include "plane/fast_loop.hpp"
#include "core/fp_requirements.hpp"

RAYKERNEL_DEFINE_FAST_LOOPS(avx512, detail::Lanes8)
