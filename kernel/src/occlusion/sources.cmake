# occlusion: rays with an interval, any-hit on a mesh, segments between two points (docs/contract.md §8): the
# segment–triangle decision, the entry points, the exact stage and references.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/occluded.cpp ${CMAKE_CURRENT_LIST_DIR}/exact_occlusion.cpp)
