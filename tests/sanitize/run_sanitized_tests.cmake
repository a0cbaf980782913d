# cmake -DSOURCE_DIR=... -DWORK_DIR=... -DFILTER=... -DENGINE_FILTER=... [-DBUILT=ON] -P run_sanitized_tests.cmake
# Builds the parsers' tests (analysis_parser_tests: test_btf_io.cpp, test_ubo2014_files.cpp; engine_parser_tests:
# test_material_file.cpp) with AddressSanitizer + UndefinedBehaviorSanitizer in their own
# tree and runs the ones matching FILTER (analysis: the BTF readers) and ENGINE_FILTER (engine: the
# material-file reader), the parsers of outside input. The tree is clang's with CARBTF_FUZZ=ON, so
# that the fuzz targets (tests/fuzz/run_fuzz.cmake) share its build.
include("${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/sanitized_tree.cmake")
require_script_arguments(SOURCE_DIR WORK_DIR FILTER ENGINE_FILTER)

configure_sanitized_tree("${SOURCE_DIR}" "${WORK_DIR}")
build_sanitized_targets("${WORK_DIR}" analysis_parser_tests engine_parser_tests)
set(ENV{ASAN_OPTIONS} "abort_on_error=0:halt_on_error=1:detect_leaks=1")
set(ENV{UBSAN_OPTIONS} "halt_on_error=1:print_stacktrace=1")
step("${WORK_DIR}/tests/analysis_parser_tests" "${FILTER}" --warn NoTests)
step("${WORK_DIR}/tests/engine_parser_tests" "${ENGINE_FILTER}" --warn NoTests)
