# The man page hitray.1, written at build time from the built command's own
# --help texts, so the page and the help cannot drift apart: the general help
# is the DESCRIPTION, each command listed under its "commands:" (a new verb
# joins by being listed there) gets a section with its `--help`, verbatim.
#   cmake -DHITRAY=<the built hitray> -DOUTPUT=<hitray.1> -DVERSION=<x.y.z> [-DVIEWER_BUILT=ON]
#         -P hitray_man.cmake
cmake_minimum_required(VERSION 3.18)

foreach(var HITRAY OUTPUT VERSION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "hitray_man.cmake: -D${var}=... is required")
  endif()
endforeach()

# The text of `hitray <args> --help`; a help that fails or is empty is an
# error of the build, not a page with a hole in it.
function(hitray_help out_var)
  execute_process(COMMAND "${HITRAY}" ${ARGN} --help
    RESULT_VARIABLE rc OUTPUT_VARIABLE text ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR text STREQUAL "")
    message(FATAL_ERROR "hitray_man.cmake: '${HITRAY} ${ARGN} --help' failed (${rc}): ${err}")
  endif()
  set(${out_var} "${text}" PARENT_SCOPE)
endfunction()

# Help text as roff in no-fill mode, shown as it is printed: backslashes
# escaped first, '-' as the minus sign \- (so options copy and paste, and man
# does not hyphenate them), a '.' or ''' at a line's start kept as text.
function(hitray_roff_verbatim out_var text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "-" "\\-" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  string(REGEX REPLACE "\n$" "" text "${text}")
  set(${out_var} ".nf\n${text}\n.fi\n" PARENT_SCOPE)
endfunction()

hitray_help(general)
# The commands: the lines "  <verb> ..." between "commands:" and the next
# blank line of the general help.
string(REGEX MATCH "\ncommands:\n(.*)" tail "${general}")
string(REGEX REPLACE "\n\n.*$" "" commands_block "${CMAKE_MATCH_1}")
string(REPLACE "\n" ";" command_lines "${commands_block}")
set(verbs "")
foreach(line IN LISTS command_lines)
  if(line MATCHES "^  ([a-z][a-z-]*) ")
    list(APPEND verbs "${CMAKE_MATCH_1}")
  endif()
endforeach()
if(NOT verbs)
  message(FATAL_ERROR "hitray_man.cmake: no commands found under 'commands:' in 'hitray --help':\n${general}")
endif()

# The one-line description: the general help's first line after the usage,
# begun in lower case as a NAME line is.
string(REGEX MATCH "\n\n([^\n]+)\n" _ "${general}")
set(summary "${CMAKE_MATCH_1}")
string(REGEX REPLACE "\\.$" "" summary "${summary}")
string(SUBSTRING "${summary}" 0 1 first)
string(SUBSTRING "${summary}" 1 -1 rest)
string(TOLOWER "${first}" first)
string(REPLACE "-" "\\-" summary "${first}${rest}")

# SYNOPSIS: each command's usage line (the first of its help); COMMANDS:
# each command's help.
set(synopsis "")
set(commands "")
foreach(verb IN LISTS verbs)
  if(verb STREQUAL "view" AND NOT VIEWER_BUILT)
    # A build without SDL2 has no hitray-view to give the help.
    string(APPEND synopsis "hitray view ...\n.br\n")
    string(APPEND commands ".SS hitray view\nNot in this build: hitray-view, the window, needs SDL2.\n")
    continue()
  endif()
  hitray_help(text ${verb})
  string(REGEX MATCH "^usage: ([^\n]+)" _ "${text}")
  if(NOT CMAKE_MATCH_1)
    message(FATAL_ERROR "hitray_man.cmake: 'hitray ${verb} --help' does not begin with 'usage: '")
  endif()
  hitray_roff_verbatim(usage "${CMAKE_MATCH_1}")
  string(REGEX REPLACE "^\\.nf\n(.*)\n\\.fi\n$" "\\1" usage "${usage}")
  string(APPEND synopsis "${usage}\n.br\n")
  hitray_roff_verbatim(text "${text}")
  string(APPEND commands ".SS hitray ${verb}\n${text}")
endforeach()

# EXIT STATUS: the general help's "exit status:" block, its own section
# (man-pages(7)), taken out of the DESCRIPTION.
string(REGEX MATCH "\nexit status:\n(.*)$" _ "${general}")
if(NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "hitray_man.cmake: 'hitray --help' has no 'exit status:' block at its end")
endif()
hitray_roff_verbatim(exit_status "${CMAKE_MATCH_1}")
string(REGEX REPLACE "\n\nexit status:\n.*$" "\n" general "${general}")
hitray_roff_verbatim(description "${general}")
set(page ".\\\" Generated at build time by cmake/hitray_man.cmake from 'hitray --help'\n")
string(APPEND page ".\\\" and each command's --help; edit those texts, not this file.\n")
string(APPEND page ".TH HITRAY 1 \"\" \"hitray ${VERSION}\" \"User Commands\"\n")
string(APPEND page ".SH NAME\nhitray \\- ${summary}\n")
string(APPEND page ".SH SYNOPSIS\n${synopsis}hitray \\-\\-help | \\-\\-version\n")
string(APPEND page ".SH DESCRIPTION\n${description}")
string(APPEND page ".SH COMMANDS\n${commands}")
string(APPEND page ".SH EXIT STATUS\n${exit_status}")
string(APPEND page ".SH ENVIRONMENT\n.TP\n.B HITRAY_SHAPE_PATH\n")
string(APPEND page "Directories (separated by ':') searched for shape modules before\n")
string(APPEND page ".I hitray/shapes\nnext to libhitray.\n")
string(APPEND page ".SH FILES\n.TP\n.I <prefix>/share/hitray/docs\n")
string(APPEND page "The documentation, among it sdl.md, the scene language.\n")
string(APPEND page ".TP\n.I <prefix>/share/hitray/scenes\nExample scenes (demo.sdl).\n")

file(WRITE "${OUTPUT}.tmp" "${page}")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
