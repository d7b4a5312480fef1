# docs/user-manual.md's tables of the methods and options are the output of
# `imagepro-cli settings --methods-markdown` (from core/settings/enum_names.cpp):
# fails when the block between the markers differs from it; with -DUPDATE=ON
# rewrites the block instead.
#   cmake -DCLI=build/src/cli/imagepro-cli -DDOC=docs/user-manual.md [-DUPDATE=ON] -P tests/cli/manual_methods.cmake
set(_begin "<!-- methods: begin, the output of `imagepro-cli settings --methods-markdown` -->\n")
set(_end "<!-- methods: end -->")
execute_process(COMMAND ${CLI} settings --methods-markdown OUTPUT_VARIABLE _tables RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "imagepro-cli settings --methods-markdown failed (${_rc})")
endif()
file(READ ${DOC} _doc)
string(FIND "${_doc}" "${_begin}" _at)
string(FIND "${_doc}" "${_end}" _stop)
if(_at EQUAL -1 OR _stop EQUAL -1 OR _stop LESS _at)
  message(FATAL_ERROR "${DOC}: no block between \"${_begin}\" and \"${_end}\"")
endif()
string(LENGTH "${_begin}" _begin_length)
math(EXPR _from "${_at} + ${_begin_length}")
math(EXPR _length "${_stop} - ${_from}")
string(SUBSTRING "${_doc}" ${_from} ${_length} _block)
if(_block STREQUAL _tables)
  return()
endif()
if(UPDATE)
  string(SUBSTRING "${_doc}" 0 ${_from} _head)
  string(SUBSTRING "${_doc}" ${_stop} -1 _tail)
  file(WRITE ${DOC} "${_head}${_tables}${_tail}")
  message(STATUS "${DOC}: method tables rewritten")
else()
  message(FATAL_ERROR "${DOC}: the method tables differ from `imagepro-cli settings --methods-markdown`; "
                      "rewrite them with: cmake -DCLI=${CLI} -DDOC=${DOC} -DUPDATE=ON -P ${CMAKE_CURRENT_LIST_FILE}")
endif()
