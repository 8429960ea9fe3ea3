# Writes the bytes of a text file as a C++ character array, so that a file of the repository (the demo scene,
# scenes/demo.json) is compiled into a program without a second copy kept in sync by hand. Run at build time:
#
#   cmake -DINPUT=FILE -DOUTPUT=FILE.inc -P cmake/EmbedText.cmake
#
# FILE.inc holds the comma-separated bytes ("0x7b,0x0a,...") to put between the braces of an array
# initializer; every byte is kept (no terminating NUL is added), whatever the file contains.
if(NOT INPUT OR NOT OUTPUT)
  message(FATAL_ERROR "EmbedText.cmake: give -DINPUT=... and -DOUTPUT=...")
endif()
file(READ "${INPUT}" hex HEX)
string(LENGTH "${hex}" length)
if(length EQUAL 0)
  message(FATAL_ERROR "EmbedText.cmake: ${INPUT} is empty")
endif()
string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," bytes "${hex}")
# 16 bytes a line, for compilers' and editors' sake.
string(REGEX REPLACE "((0x[0-9a-f][0-9a-f],){16})" "\\1\n" bytes "${bytes}")
file(WRITE "${OUTPUT}.tmp" "// Generated from ${INPUT} by cmake/EmbedText.cmake: do not edit.\n${bytes}\n")
configure_file("${OUTPUT}.tmp" "${OUTPUT}" COPYONLY)  # rewritten only when different
file(REMOVE "${OUTPUT}.tmp")
