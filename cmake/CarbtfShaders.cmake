# GLSL -> SPIR-V at build time. Each shader becomes a header <NAMESPACE/NAME.h> under OUTPUT_DIR
# holding `const uint32_t NAMESPACE_NAME[]`; nothing compiled is committed. glslang's depfile makes a
# shader rebuild when any header it includes changes.
#
#   carbtf_compile_shaders(TARGET <custom target> NAMESPACE <name> OUTPUT_DIR <dir>
#                          INCLUDE_DIRS <dirs> SOURCES <files relative to the current source dir>
#                          [VARIANTS <source>|<name>|<MACRO=value> ...])
# A variant compiles a source once more with one macro defined, into the header <NAMESPACE/name.h>.
function(carbtf_compile_shaders)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE;OUTPUT_DIR" "INCLUDE_DIRS;SOURCES;VARIANTS" ${ARGN})
  set(include_flags)
  foreach(dir IN LISTS ARG_INCLUDE_DIRS)
    list(APPEND include_flags "-I${dir}")
  endforeach()
  set(jobs)
  foreach(source IN LISTS ARG_SOURCES)
    get_filename_component(name "${source}" NAME_WE)
    list(APPEND jobs "${source}|${name}|")
  endforeach()
  list(APPEND jobs ${ARG_VARIANTS})
  set(headers)
  foreach(job IN LISTS jobs)
    string(REPLACE "|" ";" fields "${job}")
    list(LENGTH fields field_count)
    if(NOT field_count EQUAL 3)
      message(FATAL_ERROR "carbtf_compile_shaders: '${job}' is not <source>|<name>|<MACRO=value or empty>")
    endif()
    list(GET fields 0 source)
    list(GET fields 1 name)
    list(GET fields 2 define)
    set(define_flags)
    if(define)
      set(define_flags "-D${define}")
    endif()
    set(header "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}/${name}.h")
    set(depfile "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}/${name}.d")
    add_custom_command(
      OUTPUT "${header}"
      COMMAND "${CMAKE_COMMAND}" -E make_directory "${ARG_OUTPUT_DIR}/${ARG_NAMESPACE}"
      COMMAND Vulkan::glslangValidator --target-env vulkan1.2 -g0 --quiet ${include_flags} ${define_flags}
              --vn "${ARG_NAMESPACE}_${name}"
              --depfile "${depfile}"
              -o "${header}"
              "${CMAKE_CURRENT_SOURCE_DIR}/${source}"
      DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/${source}"
      DEPFILE "${depfile}"
      COMMENT "glslang: ${name}"
      VERBATIM)
    list(APPEND headers "${header}")
  endforeach()
  add_custom_target(${ARG_TARGET} DEPENDS ${headers})
endfunction()
