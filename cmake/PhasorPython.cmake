# SPDX-License-Identifier: Apache-2.0
# The Python module `phasor` (docs/python.md): pybind11 (Debian's pybind11-dev) and numpy
# (python3-numpy), built for one interpreter.
#
#   PHASOR_PYTHON = AUTO (default) | ON | OFF
#     AUTO builds the module when the interpreter, its headers, numpy and pybind11 are all found
#     (looked for again at every configure, so installing them later turns it on); ON makes a
#     missing piece a configure error; OFF never builds it.
#   Python3_EXECUTABLE: the interpreter. Default: Debian's /usr/bin/python3, where
#     python3-numpy and python3-pytest install — not the first `python3` on PATH, which may be
#     another interpreter (pyenv, a virtual environment) without them.
#   PHASOR_PYTHON_INSTALL_DIR: where `cmake --install` puts the package (default: the
#     interpreter's own site directory, sysconfig's `platlib`).
#
# The module links the same static libraries as the program, so they are compiled as
# position-independent code when it is built.

set(PHASOR_PYTHON AUTO CACHE STRING "Build the Python module: AUTO (when pybind11, the Python headers and numpy are found), ON or OFF")
set_property(CACHE PHASOR_PYTHON PROPERTY STRINGS AUTO ON OFF)

set(PHASOR_PYTHON_ENABLED OFF)
if(PHASOR_PYTHON STREQUAL "OFF" OR (PHASOR_PYTHON STREQUAL "AUTO" AND PHASOR_SANITIZE))
  # (a sanitizer build would need the sanitizer runtime preloaded into the interpreter)
  return()
endif()

if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python interpreter the phasor module is built for")
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module NumPy QUIET)
if(Python3_Interpreter_FOUND AND Python3_Development.Module_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()

set(_missing "")
if(NOT Python3_Interpreter_FOUND)
  list(APPEND _missing "a Python 3 interpreter (python3)")
endif()
if(NOT Python3_Development.Module_FOUND)
  list(APPEND _missing "the Python headers (python3-dev)")
endif()
if(NOT Python3_NumPy_FOUND)
  list(APPEND _missing "numpy (python3-numpy)")
endif()
if(NOT pybind11_FOUND)
  list(APPEND _missing "pybind11 (pybind11-dev)")
endif()
if(_missing)
  string(REPLACE ";" ", " _missing "${_missing}")
  if(PHASOR_PYTHON STREQUAL "ON")
    message(FATAL_ERROR "PHASOR_PYTHON=ON, but ${_missing} not found for ${Python3_EXECUTABLE} "
                        "(scripts/install-deps.sh installs them for Debian's /usr/bin/python3; "
                        "-DPython3_EXECUTABLE=PATH picks another interpreter)")
  endif()
  message(STATUS "Python module: off (${_missing} not found for ${Python3_EXECUTABLE})")
  return()
endif()

set(PHASOR_PYTHON_ENABLED ON)
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
# Position-independent code lets a shared library's exported functions be interposed, which keeps
# GCC from inlining them within their own file; phasor never interposes its functions, so the
# program keeps the code it has without the module.
add_compile_options(-fno-semantic-interposition)
execute_process(COMMAND ${Python3_EXECUTABLE} -c "import sysconfig; print(sysconfig.get_path('platlib'))"
                OUTPUT_VARIABLE _platlib OUTPUT_STRIP_TRAILING_WHITESPACE)
set(PHASOR_PYTHON_INSTALL_DIR "${_platlib}" CACHE PATH "Where `cmake --install` puts the Python package phasor")
message(STATUS "Python module: on, for ${Python3_EXECUTABLE} (${Python3_VERSION}); installs into ${PHASOR_PYTHON_INSTALL_DIR}")
