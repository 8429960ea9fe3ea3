# Installation: headers, libraries, the CLI, the CMake package and pkg-config files.
#
#   cmake --install build --prefix P
#
#   P/include/raykernel/...                     public headers (kernel and raykernel::testkit)
#   P/lib/libraykernel.a, libraykernel_testkit.a, libraykernel_io.a
#   P/bin/raykernel                             the CLI (when built)
#   P/lib/cmake/raykernel/                      raykernel-config.cmake, raykernel-config-version.cmake, the
#                                               exported targets raykernel::raykernel, raykernel::testkit and
#                                               raykernel::io (mesh files),
#                                               and RaykernelDependencies.cmake (GMP, gmpxx, MPFR for linking)
#   P/lib/pkgconfig/raykernel.pc, raykernel-testkit.pc, raykernel-io.pc
#
# Everything installed locates itself relative to its own directory (CMake's _IMPORT_PREFIX and
# PACKAGE_PREFIX_DIR, pkg-config's ${pcfiledir}), so an installed tree can be moved: no build or source path
# and no install prefix is written into it. (lib is lib/<multiarch> when the prefix is /usr: GNUInstallDirs.)
include_guard(GLOBAL)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RAYKERNEL_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/raykernel" CACHE STRING
    "Where raykernel's CMake package files are installed (relative to the prefix)")
set(RAYKERNEL_INSTALL_PKGCONFIGDIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig" CACHE STRING
    "Where raykernel's pkg-config files are installed (relative to the prefix)")

# The exported names: raykernel::raykernel and raykernel::testkit (NAMESPACE raykernel::). With
# BUILD_SHARED_LIBS the libraries carry the version, and 0.x releases are ABI-incompatible with each other
# (SONAME libraykernel.so.0.1).
set_target_properties(raykernel_testkit PROPERTIES EXPORT_NAME testkit)
set_target_properties(raykernel raykernel_testkit raykernel_io PROPERTIES
  VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})

# The targets' $<INSTALL_INTERFACE:include> covers the default include directory; any other is added.
set(_raykernel_includes "")
if(NOT CMAKE_INSTALL_INCLUDEDIR STREQUAL "include")
  set(_raykernel_includes INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
install(TARGETS raykernel raykernel_testkit raykernel_io
  EXPORT raykernel-targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  ${_raykernel_includes})

# Every public header, including ones added later (raykernel/testkit/plane_fuzz_decoder.hpp, ray casting): the
# directories are the targets' include directories, nothing private lives there.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/kernel/include/ ${PROJECT_SOURCE_DIR}/testkit/include/
                  ${PROJECT_SOURCE_DIR}/io/include/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")

if(TARGET raykernel_tool)
  # With BUILD_SHARED_LIBS the installed CLI finds libraykernel next to itself, wherever the tree is moved.
  file(RELATIVE_PATH _raykernel_bin_to_lib "/prefix/${CMAKE_INSTALL_BINDIR}" "/prefix/${CMAKE_INSTALL_LIBDIR}")
  set_target_properties(raykernel_tool PROPERTIES INSTALL_RPATH "$ORIGIN/${_raykernel_bin_to_lib}")
  install(TARGETS raykernel_tool RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

# The CMake package.
install(EXPORT raykernel-targets
  NAMESPACE raykernel::
  FILE raykernel-targets.cmake
  DESTINATION ${RAYKERNEL_INSTALL_CMAKEDIR})
configure_package_config_file(
  ${PROJECT_SOURCE_DIR}/cmake/raykernel-config.cmake.in
  ${PROJECT_BINARY_DIR}/raykernel-config.cmake
  INSTALL_DESTINATION ${RAYKERNEL_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API, so a request for 0.1 accepts 0.1.z only.
write_basic_package_version_file(
  ${PROJECT_BINARY_DIR}/raykernel-config-version.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${PROJECT_BINARY_DIR}/raykernel-config.cmake
  ${PROJECT_BINARY_DIR}/raykernel-config-version.cmake
  ${PROJECT_SOURCE_DIR}/cmake/RaykernelDependencies.cmake
  DESTINATION ${RAYKERNEL_INSTALL_CMAKEDIR})

# pkg-config. The prefix is computed from the .pc file's own location, so the tree stays relocatable. A
# static libraykernel needs GMP, gmpxx and MPFR on the link line of every consumer (in Libs); a shared one
# records them in Libs.private only.
if(IS_ABSOLUTE "${RAYKERNEL_INSTALL_PKGCONFIGDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}"
   OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  # Absolute directories were asked for: they cannot move with the tree, so write them as given.
  set(RAYKERNEL_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(RAYKERNEL_PC_LIBDIR "${CMAKE_INSTALL_FULL_LIBDIR}")
  set(RAYKERNEL_PC_INCLUDEDIR "${CMAKE_INSTALL_FULL_INCLUDEDIR}")
else()
  file(RELATIVE_PATH _raykernel_pc_to_prefix "/prefix/${RAYKERNEL_INSTALL_PKGCONFIGDIR}" "/prefix")
  string(REGEX REPLACE "/$" "" _raykernel_pc_to_prefix "${_raykernel_pc_to_prefix}")
  set(RAYKERNEL_PC_PREFIX "\${pcfiledir}/${_raykernel_pc_to_prefix}")
  set(RAYKERNEL_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(RAYKERNEL_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
get_target_property(_raykernel_type raykernel TYPE)
set(RAYKERNEL_PC_DEPENDENCY_LIBS "-lmpfr -lgmpxx -lgmp")
if(_raykernel_type STREQUAL "STATIC_LIBRARY")
  set(RAYKERNEL_PC_LIBS "-L\${libdir} -lraykernel ${RAYKERNEL_PC_DEPENDENCY_LIBS}")
  set(RAYKERNEL_PC_LIBS_PRIVATE "")
else()
  set(RAYKERNEL_PC_LIBS "-L\${libdir} -lraykernel")
  set(RAYKERNEL_PC_LIBS_PRIVATE "${RAYKERNEL_PC_DEPENDENCY_LIBS}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/raykernel.pc.in ${PROJECT_BINARY_DIR}/raykernel.pc @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/cmake/raykernel-testkit.pc.in ${PROJECT_BINARY_DIR}/raykernel-testkit.pc @ONLY)
configure_file(${PROJECT_SOURCE_DIR}/cmake/raykernel-io.pc.in ${PROJECT_BINARY_DIR}/raykernel-io.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/raykernel.pc ${PROJECT_BINARY_DIR}/raykernel-testkit.pc ${PROJECT_BINARY_DIR}/raykernel-io.pc
  DESTINATION ${RAYKERNEL_INSTALL_PKGCONFIGDIR})
