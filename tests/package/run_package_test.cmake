# cmake -DSOURCE_DIR=... -DWORK_DIR=... -P run_package_test.cmake
# 1. configures carbtf with analysis, CLI and tests off (the engine must build alone), builds and
#    installs it; 2. builds tests/package/consumer against the installed package; 3. runs it.
include("${CMAKE_CURRENT_LIST_DIR}/../script_steps.cmake")
require_script_arguments(SOURCE_DIR WORK_DIR)
file(REMOVE_RECURSE "${WORK_DIR}")

step("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/engine-build" -G Ninja -DCMAKE_BUILD_TYPE=Release
     -DCARBTF_BUILD_ANALYSIS=OFF -DCARBTF_BUILD_CLI=OFF -DCARBTF_BUILD_TESTS=OFF -DCARBTF_WERROR=ON
     "-DCMAKE_INSTALL_PREFIX=${WORK_DIR}/prefix")
step("${CMAKE_COMMAND}" --build "${WORK_DIR}/engine-build")
step("${CMAKE_COMMAND}" --install "${WORK_DIR}/engine-build" --component engine)
step("${CMAKE_COMMAND}" -S "${SOURCE_DIR}/tests/package/consumer" -B "${WORK_DIR}/consumer-build" -G Ninja
     -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
step("${CMAKE_COMMAND}" --build "${WORK_DIR}/consumer-build")
step("${WORK_DIR}/consumer-build/consumer")
