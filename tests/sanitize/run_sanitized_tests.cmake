# cmake -DSOURCE_DIR=... -DWORK_DIR=... -DFILTER=... -P run_sanitized_tests.cmake
# Builds the analysis tests with AddressSanitizer + UndefinedBehaviorSanitizer in their own tree and
# runs the ones matching FILTER (the parsers of outside input).
foreach(var SOURCE_DIR WORK_DIR FILTER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_sanitized_tests.cmake needs -D${var}=...")
  endif()
endforeach()

function(step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "failed (${result}): ${shown}")
  endif()
endfunction()

if(NOT EXISTS "${WORK_DIR}/CMakeCache.txt")
  step("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
       -DCARBTF_SANITIZE=ON -DCARBTF_BUILD_CLI=OFF -DCARBTF_INSTALL=OFF)
endif()
step("${CMAKE_COMMAND}" --build "${WORK_DIR}" --target analysis_tests)
set(ENV{ASAN_OPTIONS} "abort_on_error=0:halt_on_error=1:detect_leaks=1")
set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
step("${WORK_DIR}/tests/analysis_tests" "${FILTER}" --warn NoTests)
