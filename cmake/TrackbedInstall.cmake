# The C++ package (docs/cpp_package.md): cmake --install puts the libraries, their
# public headers (every library's trackbed/<library>/ folder), the trackbed program
# and trackbedConfig.cmake (with its version file) under the prefix, so that another
# CMake project's find_package(trackbed) gets the targets trackbed::runner,
# trackbed::scenario, trackbed::estimation, ... with their include folders and
# dependencies.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TRACKBED_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/trackbed)
set(_trackbed_libraries common recording sim assets render robot description perception estimation navigation teach_repeat scenario plot
                        runner experiments)
foreach(library ${_trackbed_libraries})
  set_target_properties(trackbed_${library} PROPERTIES EXPORT_NAME ${library})
  install(TARGETS trackbed_${library} EXPORT trackbedTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/${library}/trackbed
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
endforeach()
install(TARGETS trackbed RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT trackbedTargets NAMESPACE trackbed:: DESTINATION ${TRACKBED_INSTALL_CMAKEDIR})

configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/trackbedConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/trackbedConfig.cmake
                              INSTALL_DESTINATION ${TRACKBED_INSTALL_CMAKEDIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/trackbedConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/trackbedConfig.cmake
              ${CMAKE_BINARY_DIR}/cmake/trackbedConfigVersion.cmake
        DESTINATION ${TRACKBED_INSTALL_CMAKEDIR})
