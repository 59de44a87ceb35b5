# FindOpenEXRCore: OpenEXR's C library alone (libOpenEXRCore and openexr.h),
# as the imported target OpenEXR::OpenEXRCore, the name OpenEXR's own
# package gives it.
#
# hitray writes EXR through OpenEXRCore only. OpenEXR's CMake package
# (find_package(OpenEXR CONFIG)) loads Imath's too, and Debian's Imath package
# lists targets whose files ship in other packages (Imath::PyImath_Python3_11),
# so CMake warned on every configure about a library hitray never uses.
# OpenEXRCore needs nothing of Imath: it is found here directly.
#
# Sets OpenEXRCore_FOUND, OpenEXRCore_VERSION; cache: OpenEXRCore_INCLUDE_DIR,
# OpenEXRCore_LIBRARY.
find_path(OpenEXRCore_INCLUDE_DIR openexr.h PATH_SUFFIXES OpenEXR)
# Installed as libOpenEXRCore-<major>_<minor>.so with an unsuffixed link
# beside it (OpenEXR's default, OPENEXR_LIB_SUFFIX); the suffixed names are
# tried for trees that lack the link.
find_library(OpenEXRCore_LIBRARY
  NAMES OpenEXRCore OpenEXRCore-3_4 OpenEXRCore-3_3 OpenEXRCore-3_2 OpenEXRCore-3_1 OpenEXRCore-3_0)

if(OpenEXRCore_INCLUDE_DIR AND EXISTS "${OpenEXRCore_INCLUDE_DIR}/OpenEXRConfig.h")
  file(STRINGS "${OpenEXRCore_INCLUDE_DIR}/OpenEXRConfig.h" _hr_exr_version
       REGEX "^#define OPENEXR_VERSION_STRING ")
  string(REGEX REPLACE "^.*\"([0-9.]+)\".*$" "\\1" OpenEXRCore_VERSION "${_hr_exr_version}")
  unset(_hr_exr_version)
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenEXRCore
  REQUIRED_VARS OpenEXRCore_LIBRARY OpenEXRCore_INCLUDE_DIR
  VERSION_VAR OpenEXRCore_VERSION)
mark_as_advanced(OpenEXRCore_INCLUDE_DIR OpenEXRCore_LIBRARY)

if(OpenEXRCore_FOUND AND NOT TARGET OpenEXR::OpenEXRCore)
  add_library(OpenEXR::OpenEXRCore UNKNOWN IMPORTED)
  set_target_properties(OpenEXR::OpenEXRCore PROPERTIES
    IMPORTED_LOCATION "${OpenEXRCore_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenEXRCore_INCLUDE_DIR}")
endif()
