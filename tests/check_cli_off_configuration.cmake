# configuration_cli_off_bench_on: the benchmarks build without the CLI (they read the demo scene through the
# CLI's scene library, raykernel_cli_scene). Configures a fresh tree with -DRAYKERNEL_BUILD_CLI=OFF
# -DRAYKERNEL_BUILD_BENCH=ON, then compiles, with the exact commands that tree generated, the translation units
# that need the scene library's include paths: the bench's workloads and the scene library's own sources (the
# generated demo-scene source aside). That is what the CLI-off configuration changes; the targets, their
# sources and their links are the same ones the main build compiles and links in full (raykernel_bench links
# raykernel_cli_scene there), so a full build here (about 250 s of CI) would only repeat it.
#
#   cmake -DSOURCE_DIR=... -DWORK_DIR=... -DGENERATOR=... -DCXX_COMPILER=... -P check_cli_off_configuration.cmake
cmake_minimum_required(VERSION 3.20)
foreach(var SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_cli_off_configuration.cmake: ${var} is not set")
  endif()
endforeach()

file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}" -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release
          "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON -DRAYKERNEL_BUILD_CLI=OFF
          -DRAYKERNEL_BUILD_BENCH=ON -DRAYKERNEL_BUILD_TESTS=OFF -DRAYKERNEL_BUILD_FUZZERS=OFF
          -DRAYKERNEL_BUILD_PROOFS=OFF
  RESULT_VARIABLE configured OUTPUT_VARIABLE configure_log ERROR_VARIABLE configure_log)
if(NOT configured EQUAL 0)
  message(FATAL_ERROR "configuring with RAYKERNEL_BUILD_CLI=OFF and RAYKERNEL_BUILD_BENCH=ON failed:\n${configure_log}")
endif()

file(READ "${WORK_DIR}/compile_commands.json" commands)
string(JSON count LENGTH "${commands}")
math(EXPR last "${count} - 1")
set(wanted bench/workloads.cpp cli/scenes/scene.cpp cli/scenes/json_locator.cpp cli/common/text_format.cpp)
set(compiled "")
foreach(i RANGE ${last})
  string(JSON file GET "${commands}" ${i} file)
  file(RELATIVE_PATH relative "${SOURCE_DIR}" "${file}")
  if(NOT relative IN_LIST wanted)
    continue()
  endif()
  string(JSON directory GET "${commands}" ${i} directory)
  string(JSON command GET "${commands}" ${i} command)
  separate_arguments(argv UNIX_COMMAND "${command}")
  # The object goes to the tree's own path; its directory may not exist before a build.
  list(FIND argv -o at)
  if(at GREATER_EQUAL 0)
    math(EXPR at "${at} + 1")
    list(GET argv ${at} object)
    get_filename_component(object_dir "${directory}/${object}" DIRECTORY)
    file(MAKE_DIRECTORY "${object_dir}")
  endif()
  execute_process(COMMAND ${argv} WORKING_DIRECTORY "${directory}" RESULT_VARIABLE result
                  OUTPUT_VARIABLE log ERROR_VARIABLE log)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${relative} does not compile with RAYKERNEL_BUILD_CLI=OFF:\n${log}")
  endif()
  list(APPEND compiled "${relative}")
endforeach()
foreach(file IN LISTS wanted)
  if(NOT file IN_LIST compiled)
    message(FATAL_ERROR "${file} is not in the CLI-off configuration's compile commands: is raykernel_bench or "
                        "raykernel_cli_scene still configured without the CLI?")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
message(STATUS "RAYKERNEL_BUILD_CLI=OFF, RAYKERNEL_BUILD_BENCH=ON: configured; compiled ${compiled}")
