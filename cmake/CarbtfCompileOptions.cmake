# Compile settings shared by every carbtf target, through the interface target carbtf_compile_options.
set(CMAKE_CXX_STANDARD 20)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
set(CMAKE_CXX_EXTENSIONS OFF)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)

add_library(carbtf_compile_options INTERFACE)
target_compile_options(carbtf_compile_options INTERFACE
  -Wall -Wextra -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual
  # The synthesis spec (docs/design.md 4.4) needs CPU float32 to match the GPU bit for bit: no fused
  # multiply-adds and no value-changing optimisations.
  -ffp-contract=off -fno-fast-math)
if(CARBTF_WERROR)
  target_compile_options(carbtf_compile_options INTERFACE -Werror)
endif()
if(CARBTF_SANITIZE OR CARBTF_FUZZ)
  target_compile_options(carbtf_compile_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  target_link_options(carbtf_compile_options INTERFACE -fsanitize=address,undefined)
endif()
if(CARBTF_FUZZ)
  # Coverage instrumentation for libFuzzer in every library the targets link.
  target_compile_options(carbtf_compile_options INTERFACE -fsanitize=fuzzer-no-link)
endif()

# carbtf_unity_build(TARGET...): compiles each target's sources in batches of 8 when CARBTF_UNITY_BUILD
# is on. Every command file of the CLI and most test files include CLI11 or Catch2, and the engine's
# files the Vulkan headers, whose parsing and code generation cost seconds per translation unit:
# batching them roughly halves a clean build on two cores (and the sanitized tree's, and the package
# test's). CARBTF_UNITY_BUILD=OFF compiles file by file, which shows a file that misses an include.
function(carbtf_unity_build)
  if(CARBTF_UNITY_BUILD)
    set_target_properties(${ARGN} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  endif()
endfunction()
