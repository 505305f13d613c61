# Installs the libraries, headers and a CMake package config: a separate project does
#   find_package(Spatula REQUIRED) and links Spatula::mesh (etc.).
include_guard(GLOBAL)
include(CMakePackageConfigHelpers)

set(SPATULA_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Spatula)
install(EXPORT SpatulaTargets NAMESPACE Spatula:: DESTINATION ${SPATULA_CMAKE_INSTALL_DIR})
configure_package_config_file(cmake/SpatulaConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/SpatulaConfig.cmake
  INSTALL_DESTINATION ${SPATULA_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/SpatulaConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/SpatulaConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/SpatulaConfigVersion.cmake
  cmake/SpatulaDependencies.cmake DESTINATION ${SPATULA_CMAKE_INSTALL_DIR})
