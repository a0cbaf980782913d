# Install rules and the exported CMake package: an outside project does
#   find_package(carbtf REQUIRED)  and links  carbtf::engine.
include(CMakePackageConfigHelpers)

install(TARGETS carbtf_engine carbtf_model EXPORT carbtfTargets
  ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT engine
  LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}" COMPONENT engine)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/engine/include/carbtf"
  DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}" COMPONENT engine)
install(EXPORT carbtfTargets NAMESPACE carbtf:: DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/carbtf" COMPONENT engine)

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/carbtfConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/carbtfConfig.cmake"
  INSTALL_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/carbtf")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/carbtfConfigVersion.cmake" COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/carbtfConfig.cmake" "${PROJECT_BINARY_DIR}/carbtfConfigVersion.cmake"
  DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/carbtf" COMPONENT engine)

# The GLSL a host engine compiles into its own fragment shaders (carbtf_material.glsl and the layouts
# it includes); carbtfConfig.cmake points carbtf_GLSL_INCLUDE_DIR at them.
install(FILES "${PROJECT_SOURCE_DIR}/compute_shaders/include/carbtf_material.glsl"
              "${PROJECT_SOURCE_DIR}/compute_shaders/include/carbtf_gpu_shared.h"
  DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/carbtf/glsl" COMPONENT engine)
