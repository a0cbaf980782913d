# cmake -DSOURCE_DIR=... -P check_engine_layers.cmake
# The engine's layer rule (docs/design.md 2): from the bottom, the base (status, file output), material
# (the Vulkan-free model: material, its file, directions, range tiles, mip maths), vulkan, synthesis,
# render. A file may include its own layer and those below, never one above. Fails naming every include
# that points up.
if(NOT DEFINED SOURCE_DIR)
  message(FATAL_ERROR "check_engine_layers.cmake needs -DSOURCE_DIR=...")
endif()
set(layers base material vulkan synthesis render)

# The layer of a path (a file of the engine, or what an include names).
function(layer_of path out)
  set(layer base)
  foreach(candidate material vulkan synthesis render)
    if(path MATCHES "(^|/)${candidate}/")
      set(layer ${candidate})
    endif()
  endforeach()
  if(path MATCHES "internal/direction_lookup")
    set(layer material)
  elseif(path MATCHES "internal/synthesis_layout")
    set(layer synthesis)
  endif()
  list(FIND layers ${layer} rank)
  set(${out} ${rank} PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE files "${SOURCE_DIR}/engine/src/*.cpp" "${SOURCE_DIR}/engine/src/*.hpp"
     "${SOURCE_DIR}/engine/include/*.hpp" "${SOURCE_DIR}/engine/internal/*.hpp")
set(upward "")
set(checked 0)
foreach(file IN LISTS files)
  file(RELATIVE_PATH relative "${SOURCE_DIR}/engine" "${file}")
  string(REGEX REPLACE "^(src|include/carbtf/engine|internal/carbtf/engine)/" "" inside "${relative}")
  if(inside MATCHES "^carbtf/engine\\.hpp$" OR relative STREQUAL "include/carbtf/engine.hpp")
    continue()  # the umbrella header includes every layer by design
  endif()
  layer_of("${inside}" own)
  file(STRINGS "${file}" includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" target "${line}")
    if(NOT target MATCHES "^(carbtf/engine/|material/|vulkan/|synthesis/|render/)")
      continue()  # a header of the same folder, the shaders' shared header, or a library's
    endif()
    math(EXPR checked "${checked} + 1")
    string(REGEX REPLACE "^carbtf/engine/" "" target_inside "${target}")
    layer_of("${target_inside}" theirs)
    if(theirs GREATER own)
      string(APPEND upward "  engine/${relative} includes ${target}\n")
    endif()
  endforeach()
endforeach()
if(upward)
  message(FATAL_ERROR "includes that point up the engine's layers (base < material < vulkan < synthesis < render):\n${upward}")
endif()
message(STATUS "${checked} includes between the engine's layers, none pointing up")
