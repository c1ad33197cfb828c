# SPDX-License-Identifier: Apache-2.0
# Finds OpenSubdiv 3.x without Debian's config (it references static libraries that Debian does
# not ship and stops with FATAL_ERROR). Defines OpenSubdiv::osdCPU and OpenSubdiv_VERSION.
find_path(OpenSubdiv_INCLUDE_DIR opensubdiv/version.h)
find_library(OpenSubdiv_LIBRARY NAMES osdCPU)
if(OpenSubdiv_INCLUDE_DIR)
  file(STRINGS "${OpenSubdiv_INCLUDE_DIR}/opensubdiv/version.h" _osd_lines
       REGEX "#define OPENSUBDIV_VERSION_(MAJOR|MINOR|PATCH)[ \t]+[0-9]+")
  foreach(_part MAJOR MINOR PATCH)
    string(REGEX REPLACE ".*OPENSUBDIV_VERSION_${_part}[ \t]+([0-9]+).*" "\\1" _v_${_part} "${_osd_lines}")
  endforeach()
  set(OpenSubdiv_VERSION "${_v_MAJOR}.${_v_MINOR}.${_v_PATCH}")
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenSubdiv
  REQUIRED_VARS OpenSubdiv_LIBRARY OpenSubdiv_INCLUDE_DIR VERSION_VAR OpenSubdiv_VERSION)
if(OpenSubdiv_FOUND AND NOT TARGET OpenSubdiv::osdCPU)
  add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OpenSubdiv_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenSubdiv_INCLUDE_DIR}")
endif()
mark_as_advanced(OpenSubdiv_INCLUDE_DIR OpenSubdiv_LIBRARY)
