# Installs headers, libraries, the `libcam` program, the CMake package
# (find_package(libcam CONFIG COMPONENTS ...) -> libcam::core, libcam::io,
# libcam::reproject, libcam::interop, libcam::dataset, libcam::check, libcam::fit, libcam::uncertainty,
# libcam::report, libcam::calibrate, libcam::stereo) and a pkg-config file per library.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(LIBCAM_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/libcam")

# One export set per library, so that a consumer's find_package loads only the
# components it asks for (and needs only their dependencies).
foreach(layer core io reproject interop dataset check fit uncertainty report calibrate stereo)
  string(SUBSTRING ${layer} 0 1 first)
  string(TOUPPER ${first} first)
  string(SUBSTRING ${layer} 1 -1 rest)
  set(export_set "libcam${first}${rest}Targets")
  install(TARGETS libcam_${layer} EXPORT ${export_set}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT ${export_set} NAMESPACE libcam:: DESTINATION ${LIBCAM_CMAKE_DIR})
endforeach()
if(TARGET libcam_cli)
  install(TARGETS libcam_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  # Where the program looks for it (tools/CMakeLists.txt, LIBCAM_COMMANDS_MODULE_DIR).
  install(TARGETS libcam_commands LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/libcam)
endif()

# Every public header; the detail/ folders (report's OpenCV helpers, io's per-format readers
# and writers and the parsers' trees) stay inside their libraries.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/libcam/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/libcam"
  FILES_MATCHING PATTERN "*.hpp"
  REGEX "/detail(/|$)" EXCLUDE)
install(FILES "${LIBCAM_GENERATED_DIR}/libcam/version.hpp" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/libcam")

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
# libcam.pc is libcam::interop's (its historical name).
file(RELATIVE_PATH LIBCAM_PC_TO_PREFIX "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
foreach(pc libcam-core libcam-io libcam-reproject libcam libcam-dataset libcam-check libcam-fit libcam-uncertainty libcam-report
          libcam-calibrate libcam-stereo)
  configure_file("cmake/${pc}.pc.in" "${PROJECT_BINARY_DIR}/${pc}.pc" @ONLY)
  install(FILES "${PROJECT_BINARY_DIR}/${pc}.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
endforeach()
