# Installs the library, its headers and a relocatable CMake package, so that a
# downstream project needs only:
#   find_package(pcl_holefill REQUIRED)
#   target_link_libraries(app PRIVATE pcl_holefill::pcl_holefill)
include(CMakePackageConfigHelpers)

set(PCL_HOLEFILL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/pcl_holefill)

install(TARGETS pcl_holefill EXPORT pcl_holefillTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY pcl_holefill/include/pcl_holefill DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT pcl_holefillTargets NAMESPACE pcl_holefill:: DESTINATION ${PCL_HOLEFILL_CMAKE_DIR})

configure_package_config_file(cmake/pcl_holefillConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/pcl_holefillConfig.cmake
  INSTALL_DESTINATION ${PCL_HOLEFILL_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/pcl_holefillConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${CMAKE_CURRENT_BINARY_DIR}/pcl_holefillConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/pcl_holefillConfigVersion.cmake
  cmake/FindPCLComponents.cmake
  DESTINATION ${PCL_HOLEFILL_CMAKE_DIR})
