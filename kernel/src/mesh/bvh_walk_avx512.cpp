// The BVH walk compiled for AVX-512 (mesh/bvh_walk.hpp; -march=x86-64-v4 in mesh/sources.cmake): the eight child
// boxes of a node tested in one zmm register per face row.
#include "core/fp_requirements.hpp"
#include "mesh/bvh_walk.hpp"

RAYKERNEL_DEFINE_BVH_WALK(avx512)
