# SPDX-License-Identifier: Apache-2.0
# Finds OpenColorIO 2.x without Debian's broken config (wrong computed prefix).
# Defines OpenColorIO::OpenColorIO and OpenColorIO_VERSION.
find_package(PkgConfig QUIET)
if(PKG_CONFIG_FOUND)
  pkg_check_modules(PC_OCIO QUIET OpenColorIO)
endif()
find_path(OpenColorIO_INCLUDE_DIR OpenColorIO/OpenColorIO.h HINTS ${PC_OCIO_INCLUDE_DIRS})
find_library(OpenColorIO_LIBRARY NAMES OpenColorIO HINTS ${PC_OCIO_LIBRARY_DIRS})
if(OpenColorIO_INCLUDE_DIR AND EXISTS "${OpenColorIO_INCLUDE_DIR}/OpenColorIO/OpenColorABI.h")
  file(STRINGS "${OpenColorIO_INCLUDE_DIR}/OpenColorIO/OpenColorABI.h" _ocio_ver
       REGEX "#define OCIO_VERSION_STR[ \t]+\"[0-9.]+\"")
  string(REGEX REPLACE ".*\"([0-9.]+)\".*" "\\1" OpenColorIO_VERSION "${_ocio_ver}")
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenColorIO
  REQUIRED_VARS OpenColorIO_LIBRARY OpenColorIO_INCLUDE_DIR VERSION_VAR OpenColorIO_VERSION)
if(OpenColorIO_FOUND AND NOT TARGET OpenColorIO::OpenColorIO)
  add_library(OpenColorIO::OpenColorIO UNKNOWN IMPORTED)
  set_target_properties(OpenColorIO::OpenColorIO PROPERTIES
    IMPORTED_LOCATION "${OpenColorIO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenColorIO_INCLUDE_DIR}")
endif()
mark_as_advanced(OpenColorIO_INCLUDE_DIR OpenColorIO_LIBRARY)
