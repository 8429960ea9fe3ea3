# ctest proofs_no_admitted: no proof in a .v file below proofs/ (every family folder, twins/, Assumptions.v) is left
# open or replaced by an assumption.
# Fails on any of the words below anywhere in a .v file (comments included, so do not write them
# there either). Print Assumptions (check_assumptions.cmake) is the semantic check; this one also
# covers files or lemmas that no printed theorem uses.
#
# Usage: cmake -DPROOF_DIR=<proofs/> -P check_no_admitted.cmake
cmake_minimum_required(VERSION 3.20)
if(NOT DEFINED PROOF_DIR)
  message(FATAL_ERROR "check_no_admitted.cmake: -DPROOF_DIR=... is required")
endif()

set(forbidden "Admitted|admit|Admit|Axiom|Axioms|Parameter|Parameters|Conjecture")
file(GLOB_RECURSE sources ${PROOF_DIR}/*.v)
list(LENGTH sources count)
if(count EQUAL 0)
  message(FATAL_ERROR "proofs_no_admitted: no .v files in ${PROOF_DIR}")
endif()
set(failures "")
foreach(source IN LISTS sources)
  file(READ ${source} text)
  string(REGEX MATCHALL "[^A-Za-z0-9_'](${forbidden})[^A-Za-z0-9_']" hits "\n${text}\n")
  if(hits)
    list(JOIN hits " " joined)
    string(REGEX REPLACE "[\n\t]" " " joined "${joined}")
    list(APPEND failures "${source}: ${joined}")
  endif()
endforeach()
if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "proofs_no_admitted FAILED, forbidden words found:\n  ${text}")
endif()
message(STATUS "proofs_no_admitted: ${count} files, none uses ${forbidden}")
