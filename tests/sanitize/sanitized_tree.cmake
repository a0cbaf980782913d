# configure_sanitized_tree(SOURCE_DIR WORK_DIR): the build tree of the sanitized tests and the fuzz
# targets, clang with AddressSanitizer, UndefinedBehaviorSanitizer and libFuzzer's coverage; configured
# once, then built incrementally by whichever script needs it.
function(configure_sanitized_tree source_dir work_dir)
  if(EXISTS "${work_dir}/CMakeCache.txt")
    return()
  endif()
  find_program(CARBTF_CLANGXX clang++ REQUIRED)
  step("${CMAKE_COMMAND}" -S "${source_dir}" -B "${work_dir}" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
       "-DCMAKE_CXX_COMPILER=${CARBTF_CLANGXX}" -DCARBTF_SANITIZE=ON -DCARBTF_FUZZ=ON -DCARBTF_BUILD_CLI=OFF
       -DCARBTF_INSTALL=OFF)
endfunction()
