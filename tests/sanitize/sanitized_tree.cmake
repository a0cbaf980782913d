# configure_sanitized_tree(SOURCE_DIR WORK_DIR): the build tree of the sanitized tests and the fuzz
# targets, clang with AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage; configured
# once, then built incrementally by whichever script needs it.
function(configure_sanitized_tree source_dir work_dir)
  if(EXISTS "${work_dir}/CMakeCache.txt")
    return()
  endif()
  find_program(CARBTF_CLANGXX clang++ REQUIRED)
  step("${CMAKE_COMMAND}" -S "${source_dir}" -B "${work_dir}" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG"
       "-DCMAKE_CXX_COMPILER=${CARBTF_CLANGXX}" -DCARBTF_SANITIZE=ON -DCARBTF_FUZZ=ON -DCARBTF_BUILD_CLI=OFF
       -DCARBTF_INSTALL=OFF)
endfunction()

# build_sanitized_targets(WORK_DIR TARGET...): builds them, unless -DBUILT=ON says the fixture
# (build_sanitized_tree.cmake) already has; two builds at once in one tree would race.
function(build_sanitized_targets work_dir)
  if(BUILT)
    return()
  endif()
  step("${CMAKE_COMMAND}" --build "${work_dir}" --target ${ARGN})
endfunction()
