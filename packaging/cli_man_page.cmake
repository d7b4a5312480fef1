# imagepro-cli(1) from the program's own help: help2man reads the overview (--help:
# name, synopsis, options) and --version; each command's --help becomes a subsection
# of COMMANDS, as printed. Run by packaging/CMakeLists.txt:
#   cmake -DCLI=imagepro-cli -DHELP2MAN=help2man -DOUT=imagepro-cli.1.gz
#         -DDATA_FROM_BINDIR=../share/imagepro -DPACKAGE_DATADIR=/usr/share/imagepro -P cli_man_page.cmake
foreach(_var CLI HELP2MAN OUT DATA_FROM_BINDIR PACKAGE_DATADIR)
  if(NOT DEFINED ${_var})
    message(FATAL_ERROR "cli_man_page.cmake needs -D${_var}=...")
  endif()
endforeach()

function(run_cli out_var)
  execute_process(COMMAND ${CLI} ${ARGN} OUTPUT_VARIABLE _out RESULT_VARIABLE _rc)
  if(NOT _rc EQUAL 0)
    message(FATAL_ERROR "${CLI} ${ARGN} exited with ${_rc}")
  endif()
  set(${out_var} "${_out}" PARENT_SCOPE)
endfunction()

# Text for a no-fill block: backslashes escaped, no line taken for a request.
function(roff_literal out_var text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

run_cli(overview --help)
# "imagepro-cli: SUMMARY" opens the overview; the summary is the page's NAME line.
string(REGEX MATCH "^[^:\n]+: ([^\n]+)" _ "${overview}")
set(summary "${CMAKE_MATCH_1}")
string(FIND "${overview}" "Commands:\n" _start)
if(_start LESS 0 OR summary STREQUAL "")
  message(FATAL_ERROR "${CLI} --help: no summary line or no \"Commands:\" list")
endif()
string(SUBSTRING "${overview}" ${_start} -1 _list)
string(FIND "${_list}" "\n\n" _end)
string(SUBSTRING "${_list}" 0 ${_end} _list)
string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*" _names "${_list}")

set(include_text "[COMMANDS]\nEach command's own help, as \\fBimagepro-cli\\fR \\fICOMMAND\\fR \\fB--help\\fR prints it.\n")
foreach(_name IN LISTS _names)
  string(STRIP "${_name}" _name)
  run_cli(_help ${_name} --help)
  roff_literal(_help "${_help}")
  string(APPEND include_text ".SS ${_name}\n.nf\n${_help}.fi\n")
endforeach()
string(APPEND include_text
  "[FILES]\n"
  ".TP\n.I ${DATA_FROM_BINDIR}\n"
  "beside the program's folder (\\fI${PACKAGE_DATADIR}\\fR in the Debian package): the default settings "
  "(\\fIsettings.json\\fR), the sample frames (\\fIsamples/\\fR) and the printable calibration patterns "
  "(\\fIpatterns/\\fR). \\fBimagepro-cli --data-dir\\fR prints where it is.\n")

get_filename_component(_dir "${OUT}" DIRECTORY)
set(_include "${_dir}/imagepro-cli.h2m")
string(REGEX REPLACE "\\.gz$" "" _page "${OUT}")
file(WRITE "${_include}" "${include_text}")
execute_process(COMMAND ${HELP2MAN} --no-info --section 1 --name "${summary}" --include "${_include}" --output "${_page}"
                        "${CLI}"
                RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "help2man failed on ${CLI}")
endif()
# gzip -n: no name or time stamp in the file, so the same help makes the same page.
execute_process(COMMAND gzip -9nf "${_page}" RESULT_VARIABLE _rc)
if(NOT _rc EQUAL 0 OR NOT EXISTS "${_page}.gz")
  message(FATAL_ERROR "gzip failed on ${_page}")
endif()
if(NOT "${_page}.gz" STREQUAL "${OUT}")
  file(RENAME "${_page}.gz" "${OUT}")
endif()
