# ctest proofs_assumptions: compiles proofs/Assumptions.v against the compiled proofs and fails unless
#   - every theorem printed there depends only on the allowed axioms (Coq's classical real numbers,
#     functional extensionality, excluded middle: what Flocq itself uses);
#   - every theorem that a source below CITING_ROOTS (kernel/src and kernel/include, recursively: no folder is
#     left out) cites ("proofs/<family>/File.v ... `name`") is stated in that file and printed by Assumptions.v;
#     a quoted name on such a line that is one of the ctest tests of proofs/ (PROOF_TESTS, e.g. "and the test
#     `proofs_half_gap`") is a test, not a theorem. A citation of a proof file that does not exist (such as the
#     flat proofs/File.v of before the families) fails.
#
# Usage: cmake -DCOQC=coqc -DCOQ_DIR=<dir with the compiled .vo> "-DCOQ_FLAGS=-Q|<dir>|<path>|..."
#              -DPROOF_DIR=<proofs/> "-DCITING_ROOTS=<dir>|<dir>" [-DPROOF_TESTS=name,name,...]
#              -P check_assumptions.cmake
cmake_minimum_required(VERSION 3.20)
foreach(var COQC COQ_DIR COQ_FLAGS PROOF_DIR CITING_ROOTS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_assumptions.cmake: -D${var}=... is required")
  endif()
endforeach()

set(proof_tests "")
if(DEFINED PROOF_TESTS)
  string(REPLACE "," ";" proof_tests "${PROOF_TESTS}")
endif()

set(allowed_axioms
  ClassicalDedekindReals.sig_forall_dec
  ClassicalDedekindReals.sig_not_dec
  FunctionalExtensionality.functional_extensionality_dep
  Classical_Prop.classic)

string(REPLACE "|" ";" COQ_FLAGS "${COQ_FLAGS}")
string(REPLACE "|" ";" CITING_ROOTS "${CITING_ROOTS}")
configure_file(${PROOF_DIR}/Assumptions.v ${COQ_DIR}/Assumptions.v COPYONLY)
execute_process(
  COMMAND ${COQC} -q ${COQ_FLAGS} ${COQ_DIR}/Assumptions.v
  WORKING_DIRECTORY ${COQ_DIR}
  RESULT_VARIABLE status
  OUTPUT_VARIABLE output
  ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "coqc Assumptions.v failed (build the target 'proofs' first):\n${output}\n${errors}")
endif()

# Walk the output line by line. A block starts at "@@ name"; inside it, "Axioms:" opens the list of
# axioms, whose entries start in column 0 ("Name : type" or "Name" followed by indented lines).
string(REGEX MATCHALL "[^\n]*\n" lines "${output}\n")
set(current "")
set(blocks 0)
set(in_axioms FALSE)
set(printed "")
set(failures "")
foreach(line IN LISTS lines)
  string(REGEX REPLACE "\n$" "" line "${line}")
  if(line MATCHES "^@@ ([A-Za-z0-9_' ]+)$")
    set(current "${CMAKE_MATCH_1}")
    string(REPLACE " " ";" block_names "${current}")
    list(APPEND printed ${block_names})
    math(EXPR blocks "${blocks} + 1")
    set(in_axioms FALSE)
  elseif(line STREQUAL "Axioms:")
    set(in_axioms TRUE)
  elseif(line MATCHES "^Closed under the global context")
    set(in_axioms FALSE)
  elseif(in_axioms AND line MATCHES "^([^ \t:]+)")
    set(name "${CMAKE_MATCH_1}")
    if(NOT name IN_LIST allowed_axioms)
      list(APPEND failures "${current} depends on ${name}")
    endif()
  elseif(line MATCHES "^[^ \t]" AND NOT line STREQUAL "")
    list(APPEND failures "unexpected output line: ${line}")
  endif()
endforeach()

# Every "@@ name" marker in the source must have produced a block.
file(STRINGS ${PROOF_DIR}/Assumptions.v markers REGEX "idtac \"@@ ")
list(LENGTH markers expected)
list(LENGTH printed got)
if(NOT expected EQUAL blocks OR blocks EQUAL 0)
  list(APPEND failures "Assumptions.v announces ${expected} blocks, coqc printed ${blocks}")
endif()

# proofs/pending.txt: proof files the C++ cites that do not exist yet (reported, not failed, until they do).
set(pending_files "")
file(STRINGS ${PROOF_DIR}/pending.txt pending_lines REGEX "^file ")
foreach(line IN LISTS pending_lines)
  string(REGEX REPLACE "^file +([^ ]+).*$" "\\1" pending_file "${line}")
  list(APPEND pending_files "${pending_file}")
  if(EXISTS "${PROOF_DIR}/${pending_file}")
    list(APPEND failures "${pending_file} exists: remove it from proofs/pending.txt")
  endif()
endforeach()
# ... and single theorems, cited from a file that exists, whose proof has not landed yet.
set(pending_theorems "")
file(STRINGS ${PROOF_DIR}/pending.txt pending_theorem_lines REGEX "^theorem ")
foreach(line IN LISTS pending_theorem_lines)
  string(REGEX REPLACE "^theorem +([^ ]+).*$" "\\1" pending_theorem "${line}")
  list(APPEND pending_theorems "${pending_theorem}")
endforeach()
set(pending_report "")

# The theorems the C++ cites: "proofs/<family>/File.v" followed on the same line by `name`s, in every source below
# CITING_ROOTS.
set(headers "")
foreach(root IN LISTS CITING_ROOTS)
  file(GLOB_RECURSE found ${root}/*.hpp ${root}/*.cpp ${root}/*.h)
  list(APPEND headers ${found})
endforeach()
set(cited 0)
foreach(header IN LISTS headers)
  file(STRINGS ${header} citing REGEX "proofs/([a-z]+/)?[A-Za-z0-9]+\\.v")
  foreach(line IN LISTS citing)
    string(REGEX MATCH "proofs/(([a-z]+/)?[A-Za-z0-9]+)\\.v" _ "${line}")
    set(vname "${CMAKE_MATCH_1}.v")
    set(vfile "${PROOF_DIR}/${vname}")
    string(REGEX MATCHALL "`[a-z0-9_]+`" names "${line}")
    foreach(quoted IN LISTS names)
      string(REPLACE "`" "" name "${quoted}")
      if(name IN_LIST proof_tests)
        continue()
      endif()
      if(NOT EXISTS "${vfile}" AND vname IN_LIST pending_files)
        list(APPEND pending_report "${vname} `${name}` (cited by ${header})")
        continue()
      endif()
      if(name IN_LIST pending_theorems)
        if(EXISTS "${vfile}")
          file(READ "${vfile}" vtext)
          if(vtext MATCHES "(Theorem|Lemma|Corollary) ${name}[ \n]")
            list(APPEND failures "`${name}` is now proved in ${vname}: remove it from proofs/pending.txt")
          endif()
        endif()
        list(APPEND pending_report "${vname} `${name}` (cited by ${header})")
        continue()
      endif()
      math(EXPR cited "${cited} + 1")
      if(NOT EXISTS "${vfile}")
        list(APPEND failures "${header} cites ${vfile}, which does not exist")
        continue()
      endif()
      file(READ "${vfile}" vtext)
      if(NOT vtext MATCHES "(Theorem|Lemma|Corollary) ${name}[ \n]")
        list(APPEND failures "${header} cites `${name}`, not stated in ${vfile}")
      endif()
      if(NOT name IN_LIST printed)
        list(APPEND failures "${header} cites `${name}`, not printed by Assumptions.v")
      endif()
    endforeach()
  endforeach()
endforeach()
if(cited EQUAL 0)
  list(APPEND failures "no theorem citations found below ${CITING_ROOTS}")
endif()

if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "proofs_assumptions FAILED:\n  ${text}\n\ncoqc output:\n${output}")
endif()
foreach(item IN LISTS pending_report)
  message(STATUS "PENDING (proofs/pending.txt): ${item}")
endforeach()
message(STATUS "proofs_assumptions: ${got} theorems, only the allowed axioms; ${cited} citations in the C++ checked")
