// The BVH walk compiled for AVX2 (mesh/bvh_walk.hpp; -march=x86-64-v3 in kernel/CMakeLists.txt): the four child
// boxes of a node tested in one ymm register per face row.
#include "core/fp_requirements.hpp"
#include "mesh/bvh_walk.hpp"

RAYKERNEL_DEFINE_BVH_WALK(avx2)
