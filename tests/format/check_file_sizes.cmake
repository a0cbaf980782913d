# cmake -DSOURCE_DIR=... -DLIMIT=... -DFILES=<glob relative to SOURCE_DIR> [-DWHY=...] -P check_file_sizes.cmake
# Fails, naming each, where a file matched by FILES (GLOB_RECURSE) is longer than LIMIT lines. The rules
# it checks (docs/design.md 2): a command file (host/commands, 200 lines) parses options and calls what
# does the work, so one that grows holds work that belongs in host/bench, host/scene, host/report or
# host/fidelity; a file of engine/src (600 lines) holds one responsibility of its layer.
if(NOT DEFINED SOURCE_DIR OR NOT DEFINED LIMIT OR NOT DEFINED FILES)
  message(FATAL_ERROR "check_file_sizes.cmake needs -DSOURCE_DIR=... -DLIMIT=... -DFILES=...")
endif()
file(GLOB_RECURSE files "${SOURCE_DIR}/${FILES}")
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no files match ${SOURCE_DIR}/${FILES}")
endif()
set(too_long "")
foreach(file IN LISTS files)
  file(READ "${file}" text)
  string(REGEX MATCHALL "\n" breaks "${text}")
  list(LENGTH breaks line_count)
  if(line_count GREATER LIMIT)
    file(RELATIVE_PATH name "${SOURCE_DIR}" "${file}")
    string(APPEND too_long "  ${name}: ${line_count} lines\n")
  endif()
endforeach()
if(too_long)
  message(FATAL_ERROR "files of ${FILES} over ${LIMIT} lines:\n${too_long}")
endif()
message(STATUS "${count} files of ${FILES}, each at most ${LIMIT} lines")
