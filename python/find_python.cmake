# Finds what the Python package needs: an interpreter with numpy (the first `python3` on the
# PATH that imports it, else /usr/bin/python3: Debian's, where python3-numpy installs it),
# its headers, and pybind11's CMake config (Debian's pybind11-dev). Sets PDESURF_PYTHON_FOUND.
# -DPython_EXECUTABLE=... chooses the interpreter instead.
set(PDESURF_PYTHON_FOUND OFF)
if(NOT Python_EXECUTABLE)
  find_program(PDESURF_PATH_PYTHON3 python3)
  foreach(candidate IN ITEMS ${PDESURF_PATH_PYTHON3} /usr/bin/python3)
    if(EXISTS ${candidate})
      execute_process(COMMAND ${candidate} -c "import numpy" RESULT_VARIABLE has_numpy
                      OUTPUT_QUIET ERROR_QUIET)
      if(has_numpy EQUAL 0)
        set(Python_EXECUTABLE ${candidate} CACHE FILEPATH "The Python of the pdesurf package")
        break()
      endif()
    endif()
  endforeach()
endif()
if(Python_EXECUTABLE)
  find_package(Python 3.9 COMPONENTS Interpreter Development.Module)
  if(Python_FOUND)
    find_package(pybind11 2.6 CONFIG QUIET)
    if(pybind11_FOUND)
      set(PDESURF_PYTHON_FOUND ON)
    endif()
  endif()
endif()
if(NOT PDESURF_PYTHON_FOUND)
  message(STATUS "pdesurf: the Python package is not built (it needs python3 with numpy, its "
                 "headers and pybind11-dev: scripts/setup installs them)")
endif()
