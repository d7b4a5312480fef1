# One static library per pipeline stage, so a change in one stage rebuilds and
# relinks only that stage and what depends on it.
#
#   imagepro_module(NAME SOURCES a.cpp b.cpp DEPS other_module ...)
#     -> target imagepro_<NAME>, headers included as "core/<dir>/<file>.h"
#   imagepro_test(NAME SOURCES t.cpp DEPS imagepro_<module> ...)
#     -> gtest executable test_<NAME>, registered with ctest
function(imagepro_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPS" ${ARGN})
  add_library(imagepro_${name} STATIC ${M_SOURCES})
  target_include_directories(imagepro_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(imagepro_${name} PUBLIC ${M_DEPS} ${OpenCV_LIBS} Eigen3::Eigen)
  target_include_directories(imagepro_${name} SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
  if(IMAGEPRO_PYTHON)
    # Linked into the Python module as well as the programs. None of its symbols is ever
    # interposed, so calls between its functions may still be inlined.
    set_target_properties(imagepro_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
      target_compile_options(imagepro_${name} PRIVATE -fno-semantic-interposition)
    endif()
  endif()
endfunction()

function(imagepro_test name)
  cmake_parse_arguments(T "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(test_${name} ${T_SOURCES})
  target_link_libraries(test_${name} PRIVATE ${T_DEPS} GTest::gtest GTest::gtest_main)
  target_include_directories(test_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)  # support/
  target_compile_definitions(test_${name} PRIVATE
    IMAGEPRO_DATA_DIR="${IMAGEPRO_DATA_DIR}"
    IMAGEPRO_TEST_TMP="${CMAKE_BINARY_DIR}/test-tmp")
  gtest_discover_tests(test_${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()

# Adds every immediate subdirectory of the current source dir that has a
# CMakeLists.txt, in alphabetical order (modules declare their own deps).
macro(imagepro_add_subdirectories)
  file(GLOB _children RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/*)
  list(SORT _children)
  foreach(_child ${_children})
    if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/${_child} AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/${_child}/CMakeLists.txt)
      add_subdirectory(${_child})
    endif()
  endforeach()
endmacro()
