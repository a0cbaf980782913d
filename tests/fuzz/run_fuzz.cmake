# cmake -DSOURCE_DIR=... -DWORK_DIR=... [-DRUNS=N] [-DSECONDS=S] [-DBUILT=ON] -P run_fuzz.cmake
# Builds the libFuzzer targets in the sanitized tree (tests/sanitize/sanitized_tree.cmake) and runs each
# over its seed corpus (tests/fuzz/corpus/TARGET, read only; new inputs go to WORK_DIR/fuzz_corpus)
# for RUNS executions or SECONDS seconds, whichever ends first. Any crash, sanitizer report, leak or
# timeout fails the step, and libFuzzer leaves the input that caused it in WORK_DIR/fuzz_artifacts.
include("${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/../sanitize/sanitized_tree.cmake")
require_script_arguments(SOURCE_DIR WORK_DIR)
if(NOT DEFINED RUNS)
  set(RUNS 20000)
endif()
if(NOT DEFINED SECONDS)
  set(SECONDS 12)
endif()

configure_sanitized_tree("${SOURCE_DIR}" "${WORK_DIR}")
build_sanitized_targets("${WORK_DIR}" carbtf_fuzz_targets)
set(ENV{ASAN_OPTIONS} "abort_on_error=0:halt_on_error=1:detect_leaks=1")
set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
foreach(target material_file ubo2003_name manifest light_file obj_mesh ubo2014_btf)
  set(corpus "${WORK_DIR}/fuzz_corpus/${target}")
  file(REMOVE_RECURSE "${corpus}")
  file(MAKE_DIRECTORY "${corpus}" "${WORK_DIR}/fuzz_artifacts")
  message(STATUS "fuzz_${target}: up to ${RUNS} runs or ${SECONDS} s")
  step("${WORK_DIR}/tests/fuzz/fuzz_${target}" "-runs=${RUNS}" "-max_total_time=${SECONDS}" -timeout=10 -rss_limit_mb=2048
       -print_final_stats=1 "-artifact_prefix=${WORK_DIR}/fuzz_artifacts/${target}-" "${corpus}"
       "${SOURCE_DIR}/tests/fuzz/corpus/${target}")
endforeach()
