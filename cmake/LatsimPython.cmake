# The Python module (python/): whether it is built, and what that asks of the
# libraries. Included before the libraries are declared, since a module is a
# shared object and every static library linked into it must be compiled as
# position-independent code (latsim_add_library does that when LATSIM_PYTHON
# is on; the programs and tests are built as before).
#
# LATSIM_PYTHON defaults to ON, except in sanitizer and fuzz builds: an
# extension instrumented with ASan only loads into a Python that has the
# ASan runtime preloaded (LD_PRELOAD), which ctest's plain python3 has not.
# Without pybind11 (Debian's pybind11-dev) the module is skipped with a note.
set(latsim_python_default ON)
if(LATSIM_SANITIZE OR LATSIM_FUZZ)
  set(latsim_python_default OFF)
endif()
option(LATSIM_PYTHON "Build the Python module latsim (pybind11) into build/python" ${latsim_python_default})
# Debian's interpreter, which sees Debian's python3-* packages (pandas, nbclient);
# set it to a virtual environment's python to build and install for that one.
if(EXISTS "/usr/bin/python3")
  set(latsim_python_default_executable "/usr/bin/python3")
else()
  find_program(LATSIM_PYTHON3_ON_PATH NAMES python3)
  set(latsim_python_default_executable "${LATSIM_PYTHON3_ON_PATH}")
endif()
set(LATSIM_PYTHON_EXECUTABLE "${latsim_python_default_executable}" CACHE FILEPATH "The Python the module is built for")

if(LATSIM_PYTHON)
  # pybind11's classic finder reads PYTHON_EXECUTABLE; without it, it takes
  # the first python3 on PATH, which need not be the one asked for.
  set(PYTHON_EXECUTABLE "${LATSIM_PYTHON_EXECUTABLE}" CACHE FILEPATH "" FORCE)
  find_package(pybind11 2.6 CONFIG QUIET)
  if(pybind11_FOUND)
    message(STATUS "latsim Python module: for ${LATSIM_PYTHON_EXECUTABLE} (pybind11 ${pybind11_VERSION})")
  else()
    message(STATUS "latsim Python module: skipped, no pybind11 (install pybind11-dev, or -DLATSIM_PYTHON=OFF)")
    set(LATSIM_PYTHON OFF)
  endif()
endif()
