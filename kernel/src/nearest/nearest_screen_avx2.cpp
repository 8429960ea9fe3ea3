// The nearest_hit screen compiled for AVX2 (nearest/nearest_screen.hpp; -march=x86-64-v3 in
// kernel/CMakeLists.txt): four planes in one ymm register per value.
#include "core/fp_requirements.hpp"
#include "nearest/nearest_screen.hpp"

RAYKERNEL_DEFINE_NEAREST_SCREEN(avx2, detail::Lanes4)
