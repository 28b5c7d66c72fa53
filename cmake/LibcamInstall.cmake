# Installs headers, libraries, the `libcam` program, the CMake package
# (find_package(libcam CONFIG) -> libcam::core, libcam::interop, libcam::fit) and pkg-config files.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LIBCAM_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/libcam")

install(TARGETS libcam_core EXPORT libcamCoreTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS libcam_interop EXPORT libcamInteropTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS libcam_fit EXPORT libcamFitTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
if(TARGET libcam_cli)
  install(TARGETS libcam_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()

install(DIRECTORY "${PROJECT_SOURCE_DIR}/libcam/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/libcam"
  FILES_MATCHING PATTERN "*.hpp")
install(FILES "${LIBCAM_GENERATED_DIR}/libcam/version.hpp" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/libcam")

install(EXPORT libcamCoreTargets NAMESPACE libcam:: DESTINATION ${LIBCAM_CMAKE_DIR})
install(EXPORT libcamInteropTargets NAMESPACE libcam:: DESTINATION ${LIBCAM_CMAKE_DIR})
install(EXPORT libcamFitTargets NAMESPACE libcam:: DESTINATION ${LIBCAM_CMAKE_DIR})
configure_package_config_file(cmake/libcamConfig.cmake.in "${PROJECT_BINARY_DIR}/libcamConfig.cmake"
  INSTALL_DESTINATION ${LIBCAM_CMAKE_DIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/libcamConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES
  "${PROJECT_BINARY_DIR}/libcamConfig.cmake"
  "${PROJECT_BINARY_DIR}/libcamConfigVersion.cmake"
  "${PROJECT_SOURCE_DIR}/cmake/FindMrcal.cmake"
  DESTINATION ${LIBCAM_CMAKE_DIR})

# pkg-config files find the prefix from their own folder, so an installed tree can move.
file(RELATIVE_PATH LIBCAM_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
foreach(pc libcam-core libcam libcam-fit)
  configure_file("cmake/${pc}.pc.in" "${PROJECT_BINARY_DIR}/${pc}.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/${pc}.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
endforeach()
