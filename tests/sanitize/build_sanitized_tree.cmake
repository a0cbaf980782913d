# cmake -DSOURCE_DIR=... -DWORK_DIR=... -P build_sanitized_tree.cmake
# Configures and builds the sanitized tree (tests/sanitize/sanitized_tree.cmake) with everything the
# sanitized tests and the fuzz runs need. CTest runs it once as the fixture those tests require, so that
# they can then run side by side without building.
include("${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/sanitized_tree.cmake")
require_script_arguments(SOURCE_DIR WORK_DIR)

configure_sanitized_tree("${SOURCE_DIR}" "${WORK_DIR}")
build_sanitized_targets("${WORK_DIR}" analysis_parser_tests engine_parser_tests carbtf_fuzz_targets)
