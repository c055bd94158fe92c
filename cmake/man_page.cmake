# man_page.cmake - clrt.1 from the binary's own help, by help2man.
# cmake -DCLRT=path/to/clrt -DHELP2MAN=help2man -DINCLUDE=packaging/clrt.h2m -DOUT=clrt.1 -P man_page.cmake
# help2man writes NAME, SYNOPSIS, DESCRIPTION and OPTIONS from `clrt --help`
# and `clrt --version`; this script adds a COMMANDS section with every
# subcommand's --help (the list read from the top-level help, not repeated
# here) to the hand-written sections of INCLUDE.
# (In a CLRT_SANITIZE build, a leak report at exit must not fail the build.)
set(ENV{ASAN_OPTIONS} "detect_leaks=0")
execute_process(COMMAND ${CLRT} --help OUTPUT_VARIABLE top RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CLRT} --help failed (${rc})")
endif()
string(REPLACE "\n" ";" lines "${top}")
set(in_list FALSE)
set(commands)
foreach(line IN LISTS lines)
  if(line MATCHES "^Subcommands:")
    set(in_list TRUE)
  elseif(in_list AND line MATCHES "^  ([a-z][a-z0-9-]*)( |$)")
    list(APPEND commands ${CMAKE_MATCH_1})
  elseif(in_list AND NOT line STREQUAL "")
    set(in_list FALSE)
  endif()
endforeach()
if(NOT commands)
  message(FATAL_ERROR "no subcommands found in `${CLRT} --help`")
endif()

# roff: a backslash is \e, a minus sign \- (not a hyphen); a line starting with . or ' is protected with \&.
function(roff_text text out)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

file(READ ${INCLUDE} include_text)
string(APPEND include_text "\n[COMMANDS]\n")
foreach(command IN LISTS commands)
  execute_process(COMMAND ${CLRT} ${command} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${CLRT} ${command} --help failed (${rc})")
  endif()
  roff_text("${help}" help)
  string(APPEND include_text ".SS \"clrt ${command}\"\n.nf\n${help}.fi\n")
endforeach()
# The version from the binary's first --version line ("clrt 0.1.0"); the
# lines after it (how it was built) stay out of the page.
execute_process(COMMAND ${CLRT} --version OUTPUT_VARIABLE version RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT version MATCHES "^clrt ([^\n]+)")
  message(FATAL_ERROR "${CLRT} --version failed (${rc}): ${version}")
endif()
set(version ${CMAKE_MATCH_1})
get_filename_component(out_dir ${OUT} DIRECTORY)
set(generated ${out_dir}/clrt.h2m)
file(WRITE ${generated} "${include_text}")
execute_process(
  COMMAND ${HELP2MAN} --no-info --section 1 --name "OpenCL Whitted ray tracer with a double-precision reference"
          --version-string ${version} --include ${generated} --output ${OUT}.tmp ${CLRT}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "help2man failed (${rc})")
endif()
file(RENAME ${OUT}.tmp ${OUT})
