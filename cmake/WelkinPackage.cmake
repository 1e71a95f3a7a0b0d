# find_package(Welkin) support for the installed tree.
include(CMakePackageConfigHelpers)
install(EXPORT WelkinTargets NAMESPACE Welkin:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Welkin)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/WelkinConfig.cmake.in
  ${CMAKE_BINARY_DIR}/WelkinConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Welkin)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/WelkinConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/WelkinConfig.cmake ${CMAKE_BINARY_DIR}/WelkinConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Welkin)
