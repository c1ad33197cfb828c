# SPDX-License-Identifier: Apache-2.0
# The five libraries of the design card plus TBB, GoogleTest and Google Benchmark, with fixes for
# Debian 12's broken CMake configs (docs: ../shared/docs/dependencies.md, summarised in
# docs/building.md).

find_package(TBB REQUIRED COMPONENTS tbb)
find_package(embree 3.13 REQUIRED)

# OpenImageIO 2.4 (Debian): its exported target lists /usr/include/opencv4, which does not exist
# unless OpenCV is installed; CMake refuses to generate with a missing include directory. Drop
# every non-existent directory from the target's include properties.
function(phasor_drop_missing_include_dirs target)
  foreach(_prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(_dirs ${target} ${_prop})
    if(_dirs)
      set(_kept)
      foreach(_d IN LISTS _dirs)
        if(EXISTS "${_d}" OR _d MATCHES "^\\$<")
          list(APPEND _kept "${_d}")
        endif()
      endforeach()
      set_target_properties(${target} PROPERTIES ${_prop} "${_kept}")
    endif()
  endforeach()
endfunction()
find_package(OpenImageIO 2.4 CONFIG REQUIRED)
phasor_drop_missing_include_dirs(OpenImageIO::OpenImageIO)
if(TARGET OpenImageIO::OpenImageIO_Util)
  phasor_drop_missing_include_dirs(OpenImageIO::OpenImageIO_Util)
endif()

# OpenColorIO and OpenSubdiv: project-owned Find modules (cmake/Find*.cmake), because Debian's
# configs compute a wrong prefix (OCIO) or reference static libraries that are not shipped (OSD).
find_package(OpenColorIO 2.1 REQUIRED)
find_package(OpenSubdiv 3.5 REQUIRED)
find_package(TinyGLTF 2.7 REQUIRED)
find_package(Threads REQUIRED)
# libcerf (complex error / Faddeeva function; Debian ships no CMake config).
find_library(CERF_LIBRARY cerf REQUIRED)
find_path(CERF_INCLUDE_DIR cerf.h)

# MPI (plain MPI-3; Debian: libopenmpi-dev openmpi-bin) for distributed renders, docs/distributed.md.
# PHASOR_MPI: ON by default when an MPI is found; OFF builds the one-process program.
# The C API only: no deprecated C++ bindings (MPI_CXX_SKIP_MPICXX).
set(MPI_CXX_SKIP_MPICXX ON)
find_package(MPI COMPONENTS CXX QUIET)
option(PHASOR_MPI "Distributed renders, sweeps and compare runs over MPI (docs/distributed.md)" ${MPI_CXX_FOUND})
if(PHASOR_MPI AND NOT MPI_CXX_FOUND)
  message(FATAL_ERROR "PHASOR_MPI=ON but no MPI was found (Debian: apt-get install libopenmpi-dev openmpi-bin)")
endif()
if(PHASOR_MPI)
  find_program(PHASOR_MPIEXEC NAMES mpirun mpiexec HINTS ${MPIEXEC_EXECUTABLE})
endif()

if(PHASOR_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(PHASOR_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()
