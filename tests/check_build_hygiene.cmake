# ctest build_hygiene: checks about how raykernel is built and where things live, that no compiler or unit
# test sees:
#   - every translation unit of the project is compiled with the warnings of raykernel_warnings (-Wall
#     -Wextra for GCC and Clang; cmake/RaykernelWarnings.cmake), read from compile_commands.json;
#   - the CLI library keeps its include directory and its testkit dependency to itself (what it exports:
#     INTERFACE_INCLUDE_DIRECTORIES and INTERFACE_LINK_LIBRARIES, given as CLI_INCLUDES and CLI_LINKS);
#   - the built-in demo scene has one copy, scenes/demo.json (compiled in at build time), not a second one
#     in the CLI's sources;
#   - outside kernel/, the code and the README cite the project's own documents (docs/contract.md,
#     docs/ray-casting.md), not "the lecture" or "the seed" or a CONTRACT file outside the repository.
#
#   cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DCOMPILE_COMMANDS=... -DCOMPILER_ID=... -DCLI_INCLUDES=... -DCLI_LINKS=...
#         -P tests/check_build_hygiene.cmake
set(problems "")

# ---- Warnings on every translation unit ----
if(COMPILER_ID MATCHES "^(GNU|Clang|AppleClang)$")
  file(READ "${COMPILE_COMMANDS}" commands)
  string(JSON count LENGTH "${commands}")
  math(EXPR last "${count} - 1")
  set(checked 0)
  foreach(i RANGE ${last})
    string(JSON file GET "${commands}" ${i} file)
    string(JSON command ERROR_VARIABLE no_command GET "${commands}" ${i} command)
    if(no_command)
      string(JSON command GET "${commands}" ${i} arguments)
    endif()
    if(NOT file MATCHES "^${SOURCE_DIR}/")
      continue()
    endif()
    math(EXPR checked "${checked} + 1")
    foreach(flag -Wall -Wextra)
      if(NOT command MATCHES "(^|[ ;\"])${flag}([ ;\"]|$)")
        string(APPEND problems "  ${file}: compiled without ${flag}\n")
      endif()
    endforeach()
  endforeach()
  if(checked EQUAL 0)
    string(APPEND problems "  ${COMPILE_COMMANDS} lists no source of the project\n")
  endif()
endif()

# ---- What the CLI library exports ----
if(CLI_INCLUDES MATCHES "/cli")
  string(APPEND problems "  raykernel_cli exports its include directory: ${CLI_INCLUDES}\n")
endif()
# (CLI_LINKS comes comma-separated, with "$<" written "GENEX<".)
string(REPLACE "," ";" CLI_LINKS "${CLI_LINKS}")
foreach(item IN LISTS CLI_LINKS)
  if(item MATCHES "testkit" AND NOT item MATCHES "^GENEX<LINK_ONLY:")
    string(APPEND problems "  raykernel_cli exports its testkit dependency: ${item}\n")
  endif()
endforeach()

# ---- One copy of the demo scene ----
file(READ "${SOURCE_DIR}/scenes/demo.json" demo)
string(REGEX MATCH "\"description\": \"[^\"]*\"" description "${demo}")
string(SUBSTRING "${description}" 16 60 description)
file(GLOB_RECURSE cli_sources "${SOURCE_DIR}/cli/*.cpp" "${SOURCE_DIR}/cli/*.hpp" "${SOURCE_DIR}/cli/*.inc")
foreach(source IN LISTS cli_sources)
  file(READ "${source}" text)
  string(FIND "${text}" "${description}" at)
  if(NOT at EQUAL -1)
    string(APPEND problems "  ${source} holds a copy of scenes/demo.json\n")
  endif()
endforeach()

# ---- Citations ----
file(GLOB_RECURSE cited
  "${SOURCE_DIR}/cli/*" "${SOURCE_DIR}/tests/*.cpp" "${SOURCE_DIR}/tests/*.hpp" "${SOURCE_DIR}/tests/CMakeLists.txt"
  "${SOURCE_DIR}/fuzz/*.cpp" "${SOURCE_DIR}/fuzz/*.hpp" "${SOURCE_DIR}/fuzz/README.md" "${SOURCE_DIR}/bench/*.cpp"
  "${SOURCE_DIR}/bench/*.hpp" "${SOURCE_DIR}/testkit/*.cpp" "${SOURCE_DIR}/testkit/*.hpp" "${SOURCE_DIR}/scenes/*"
  "${SOURCE_DIR}/examples/*.cpp" "${SOURCE_DIR}/README.md")  # (README.md: every README of the tree)
foreach(source IN LISTS cited)
  # Not build directories inside the source tree, nor git's files.
  file(RELATIVE_PATH relative "${SOURCE_DIR}" "${source}")
  if(relative MATCHES "^(build[^/]*|\\.git)/" OR (BINARY_DIR AND source MATCHES "^${BINARY_DIR}/"))
    continue()
  endif()
  file(STRINGS "${source}" lines REGEX "lecture|the seed's|as in the seed|CONTRACT[ .§]|shared/CONTRACT")
  foreach(line IN LISTS lines)
    string(APPEND problems "  ${source}: cites a document outside the repository: ${line}\n")
  endforeach()
endforeach()

if(problems)
  message(FATAL_ERROR "build hygiene:\n${problems}")
endif()
message(STATUS "build hygiene: ok")
