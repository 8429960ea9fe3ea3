// The BVH walk for any x86-64 (SSE2) or other target (mesh/bvh_walk.hpp).
#include "core/fp_requirements.hpp"
#include "mesh/bvh_walk.hpp"

RAYKERNEL_DEFINE_BVH_WALK(portable)
