# Finds libmrcal (Debian: libmrcal-dev), which ships no CMake or pkg-config file.
# Defines the imported target Mrcal::mrcal. Its C headers have no extern "C" guards:
# include them only through libcam/interop/detail/mrcal_c.hpp, which wraps them.
find_path(Mrcal_INCLUDE_DIR NAMES mrcal/mrcal.h)
find_library(Mrcal_LIBRARY NAMES mrcal)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Mrcal REQUIRED_VARS Mrcal_LIBRARY Mrcal_INCLUDE_DIR)

if(Mrcal_FOUND AND NOT TARGET Mrcal::mrcal)
  add_library(Mrcal::mrcal UNKNOWN IMPORTED)
  # SYSTEM: mrcal's headers use C idioms (anonymous structs, flexible array members)
  # that -Wpedantic reports in C++; they are not ours to fix.
  set_target_properties(Mrcal::mrcal PROPERTIES
    IMPORTED_LOCATION "${Mrcal_LIBRARY}"
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${Mrcal_INCLUDE_DIR}"
    INTERFACE_INCLUDE_DIRECTORIES "${Mrcal_INCLUDE_DIR}")
endif()
mark_as_advanced(Mrcal_INCLUDE_DIR Mrcal_LIBRARY)
