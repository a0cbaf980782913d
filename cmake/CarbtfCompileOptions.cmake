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
