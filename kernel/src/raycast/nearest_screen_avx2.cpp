// The nearest_hit screen compiled for AVX2 (raycast/nearest_screen.hpp; -march=x86-64-v3 in
// kernel/CMakeLists.txt): four planes in one ymm register per value.
#include "certified/fp_requirements.hpp"
#include "raycast/nearest_screen.hpp"

RAYKERNEL_DEFINE_NEAREST_SCREEN(avx2, detail::Lanes4)
