# cmake -DSOURCE_DIR=... -DCLANG_FORMAT=... -P check_format.cmake
# Fails, with clang-format's own diagnostics, unless every C/C++ file of the project is as the
# repository's .clang-format lays it out (docs/design.md: code style).
foreach(argument SOURCE_DIR CLANG_FORMAT)
  if(NOT DEFINED ${argument})
    message(FATAL_ERROR "check_format.cmake needs -D${argument}=...")
  endif()
endforeach()
set(files)
foreach(folder analysis engine host tests compute_shaders)
  file(GLOB_RECURSE found "${SOURCE_DIR}/${folder}/*.cpp" "${SOURCE_DIR}/${folder}/*.hpp" "${SOURCE_DIR}/${folder}/*.h"
       "${SOURCE_DIR}/${folder}/*.c")
  list(APPEND files ${found})
endforeach()
list(LENGTH files count)
if(count EQUAL 0)
  message(FATAL_ERROR "no C/C++ files found under ${SOURCE_DIR}")
endif()
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run -Werror ${files} RESULT_VARIABLE result ERROR_VARIABLE diagnostics)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "${diagnostics}\nnot clang-format clean (run: clang-format -i FILE)")
endif()
message(STATUS "${count} C/C++ files are clang-format clean")
