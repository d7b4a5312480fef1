# The Python module (src/python): pybind11 and a Python 3 that has numpy. Decides
# IMAGEPRO_PYTHON before the core is added, since the core's static libraries must then
# be position-independent code to be linked into the module (imagepro_module).
#
# The first python3 on the PATH may be an interpreter of its own (pyenv, a virtualenv)
# without numpy; the module is built for the first one that has numpy (Debian's
# python3-numpy), or for Python_EXECUTABLE when given.
if(NOT DEFINED Python_EXECUTABLE)
  string(REPLACE ":" ";" _path_dirs "$ENV{PATH}")
  foreach(_dir ${_path_dirs} /usr/bin)
    if(NOT Python_EXECUTABLE AND EXISTS "${_dir}/python3")
      execute_process(COMMAND "${_dir}/python3" -c "import numpy" RESULT_VARIABLE _no_numpy OUTPUT_QUIET ERROR_QUIET)
      if(_no_numpy EQUAL 0)
        set(Python_EXECUTABLE "${_dir}/python3" CACHE FILEPATH "The Python the module is built and tested for")
      endif()
    endif()
  endforeach()
endif()

set(_python_default OFF)
# Sanitizer and fuzzing builds leave the module out: its test would need the sanitizer's
# runtime preloaded into the interpreter.
if(NOT IMAGEPRO_SANITIZE AND Python_EXECUTABLE)
  find_package(Python 3 QUIET COMPONENTS Interpreter Development.Module NumPy)
  if(Python_FOUND)
    find_package(pybind11 2.6 CONFIG QUIET)  # with Python found first it uses FindPython's targets
    if(pybind11_FOUND)
      set(_python_default ON)
    endif()
  endif()
endif()

option(IMAGEPRO_PYTHON "Build the Python module imagepro (pybind11, numpy)" ${_python_default})
if(IMAGEPRO_PYTHON)
  if(NOT _python_default)
    message(FATAL_ERROR "IMAGEPRO_PYTHON needs pybind11-dev, python3-dev and python3-numpy (Python: '${Python_EXECUTABLE}')")
  endif()
  message(STATUS "Python module: ${Python_EXECUTABLE} (Python ${Python_VERSION}, pybind11 ${pybind11_VERSION})")
else()
  message(STATUS "Python module: not built (IMAGEPRO_PYTHON is OFF)")
endif()
