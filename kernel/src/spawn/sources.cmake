# spawn: the origin of a secondary ray that never re-hits its surface (docs/contract.md §9), certified, then decided exactly.
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/spawn.cpp ${CMAKE_CURRENT_LIST_DIR}/secondary_exact.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/spawn_certified.cpp)
