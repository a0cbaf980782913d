# Install rules and the exported CMake package: an outside project does
#   find_package(carbtf REQUIRED)  and links  carbtf::engine.
include(CMakePackageConfigHelpers)

install(TARGETS carbtf_engine EXPORT carbtfTargets
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
