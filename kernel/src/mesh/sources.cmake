# mesh: triangle meshes (docs/contract.md §7): validation, the BVH and its walk, nearest hit, inside, the
# exact reference.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/mesh_validate.cpp ${CMAKE_CURRENT_LIST_DIR}/bvh.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/bvh_walk_portable.cpp ${CMAKE_CURRENT_LIST_DIR}/prepared_mesh.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/inside.cpp ${CMAKE_CURRENT_LIST_DIR}/inside_grid.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/nearest_mesh.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/exact_mesh.cpp)
# The BVH walk (bvh_walk.hpp), once per instruction set: AVX-512, AVX2, or portable.
if(RAYKERNEL_ISA_VARIANTS)
  target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/bvh_walk_avx2.cpp ${CMAKE_CURRENT_LIST_DIR}/bvh_walk_avx512.cpp)
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/bvh_walk_avx2.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v3")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/bvh_walk_avx512.cpp PROPERTIES COMPILE_OPTIONS "-march=x86-64-v4")
  set_source_files_properties(${CMAKE_CURRENT_LIST_DIR}/bvh.cpp PROPERTIES COMPILE_DEFINITIONS RAYKERNEL_BVH_WALK_AVX2)
endif()
