# The man page says what the command's --help says: rendered by groff (with
# every warning on, any of which fails), it holds each command listed by
# `hitray --help` under its own heading, with every line of that command's
# `--help` and of the general help, as printed. The page is generated from
# the help (cmake/hitray_man.cmake); this checks the generation, in the
# page's rendered form, without relying on how it escapes anything.
# Variables: HITRAY (the built command) PAGE (hitray.1)
cmake_minimum_required(VERSION 3.18)
include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

expect_file("${PAGE}")
# Looked for now, not at configure time: `make test` installs groff after
# `make build` has configured the tree.
find_program(GROFF groff)
if(NOT GROFF)
  message("skipped: groff is not installed (Debian: groff-base), so the page cannot be read")
  return()
endif()
execute_process(COMMAND "${GROFF}" -man -Tascii -ww -P-c -P-b -P-u "${PAGE}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE rendered ERROR_VARIABLE warnings)
if(NOT rc EQUAL 0 OR NOT warnings STREQUAL "")
  message(FATAL_ERROR "groff -ww on ${PAGE} (${rc}):\n${warnings}")
endif()
# The rendered lines, each stripped of the page's indent.
string(REGEX REPLACE "\n[ ]+" "\n" rendered "\n${rendered}")

# Every non-blank line of TEXT, stripped, is a line of the rendered page.
function(expect_lines_in_page what text)
  string(REPLACE ";" "\\;" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(line STREQUAL "")
      continue()
    endif()
    string(FIND "${rendered}" "\n${line}\n" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "the man page lacks this line of ${what}:\n  ${line}\n"
        "rendered page:\n${rendered}")
    endif()
  endforeach()
endfunction()

run_checked("hitray --help" "${HITRAY}" --help)
set(general "${LAST_OUTPUT}")
# The help's "exit status:" block is the page's EXIT STATUS section.
string(REPLACE "\nexit status:\n" "\nEXIT STATUS\n" general_on_page "${general}")
if(general_on_page STREQUAL general)
  message(FATAL_ERROR "'hitray --help' lists no exit status:\n${general}")
endif()
expect_lines_in_page("'hitray --help'" "${general_on_page}")
string(REGEX MATCH "\ncommands:\n(.*)" _ "${general}")
string(REGEX REPLACE "\n\n.*$" "" block "${CMAKE_MATCH_1}")
string(REGEX MATCHALL "(^|\n)  [a-z][a-z-]* " verbs "${block}")
list(LENGTH verbs count)
if(count LESS 4)
  message(FATAL_ERROR "expected at least 4 commands under 'commands:' in 'hitray --help':\n${general}")
endif()
foreach(verb IN LISTS verbs)
  string(STRIP "${verb}" verb)
  string(FIND "${rendered}" "\nhitray ${verb}\n" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the man page has no section 'hitray ${verb}'")
  endif()
  run_checked("hitray ${verb} --help" "${HITRAY}" ${verb} --help)
  expect_lines_in_page("'hitray ${verb} --help'" "${LAST_OUTPUT}")
endforeach()
message(STATUS "${PAGE}: ${count} commands, every help line present")
