# GLSL -> SPIR-V at build time. Each shader becomes a header <NAMESPACE/NAME.h> under OUTPUT_DIR
# holding `const uint32_t NAMESPACE_NAME[]`; nothing compiled is committed. glslang's depfile makes a
# shader rebuild when any header it includes changes.
#
#   carbtf_compile_shaders(TARGET <custom target> NAMESPACE <name> OUTPUT_DIR <dir>
#                          INCLUDE_DIRS <dirs> SOURCES <files relative to the current source dir>)
function(carbtf_compile_shaders)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE;OUTPUT_DIR" "INCLUDE_DIRS;SOURCES" ${ARGN})
  set(include_flags)
  foreach(dir IN LISTS ARG_INCLUDE_DIRS)
    list(APPEND include_flags "-I${dir}")
  endforeach()
  set(headers)
  foreach(source IN LISTS ARG_SOURCES)
    get_filename_component(name "${source}" NAME_WE)
    set(header "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}/${name}.h")
    set(depfile "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}/${name}.d")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND "${CMAKE_COMMAND}" -E make_directory "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}"
      COMMAND Vulkan::glslangValidator --target-env vulkan1.2 -g0 --quiet ${include_flags}
              --vn "${ARG_NAMESPACE}_${name}"
              --depfile "${depfile}"
              -o "${header}"
              "${CMAKE_CURRENT_SOURCE_DIR}/${source}"
      MAIN_DEPENDENCY "${CMAKE_CURRENT_SOURCE_DIR}/${source}"
      DEPFILE "${depfile}"
      COMMENT "glslang: ${source}"
      VERBATIM)
    list(APPEND headers "${header}")
  endforeach()
  add_custom_target(${ARG_TARGET} DEPENDS ${headers})
endfunction()
