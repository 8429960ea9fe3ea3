# camera: transforms and cameras (points w = 1, directions w = 0; rays from pixel centres).
target_sources(raykernel PRIVATE ${CMAKE_CURRENT_LIST_DIR}/transform.cpp ${CMAKE_CURRENT_LIST_DIR}/camera.cpp)
