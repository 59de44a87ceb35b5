# The layering check: no layer of lib/ reaches up.
#   - an #include names a lib/ header with its folder, and that folder is the
#     layer's own or one of its USES (lib/CMakeLists.txt);
#   - a call (an undefined symbol of a layer's object files, by nm) to a
#     function defined by another layer goes to one of its USES, or, from a
#     CLIENT layer, to a function the library exports (the public API);
#   - a crossing listed by hitray_layer_crossing is tolerated, and one listed
#     that no longer occurs is a problem (the list only shrinks);
#   - neither the USES nor the calls between layers make a loop;
#   - each header's include guard is named for its folder and file;
#   - the prefixes tell exported from internal: a function or variable that
#     lib/ defines for its other files is hri_*, a name the library exports
#     is hr_* (and every hr_* it defines is exported), so no static
#     function is hr_* (one in a header, shared by its includers, is hri_*).
# Every problem is reported (file:line:col for includes), then the check fails.
# Variables: LIB_DIR (the sources' lib/), MANIFEST (written by
# tests/layering/CMakeLists.txt: HITRAY_LAYERS, HITRAY_LAYER_USES_<layer>,
# HITRAY_LAYER_OBJECTS_<layer>, HITRAY_CLIENT_LAYERS, HITRAY_LAYER_CROSSINGS,
# HITRAY_LIBRARY), NM.
cmake_minimum_required(VERSION 3.18)

include("${MANIFEST}")
set(problems 0)
macro(problem text)
  message("${text}")
  math(EXPR problems "${problems} + 1")
endmacro()

# --- includes
file(GLOB lib_folders RELATIVE "${LIB_DIR}" LIST_DIRECTORIES true "${LIB_DIR}/*")
foreach(layer IN LISTS HITRAY_LAYERS)
  file(GLOB sources RELATIVE "${LIB_DIR}" "${LIB_DIR}/${layer}/*.c" "${LIB_DIR}/${layer}/*.h")
  foreach(source IN LISTS sources)
    file(READ "${LIB_DIR}/${source}" text)
    # A header's include guard is named for its place, so that a file moved
    # or renamed shows a stale one: HITRAY_LIB_<FOLDER>_<NAME>_H, the folder
    # once where the name starts with it (sdl/sdl_lexer.h: HITRAY_LIB_SDL_LEXER_H).
    if(source MATCHES "\\.h$")
      get_filename_component(base "${source}" NAME_WE)
      string(TOUPPER "${base}" guard)
      string(TOUPPER "${layer}" upper_layer)
      if(NOT guard MATCHES "^${upper_layer}(_|$)")
        set(guard "${upper_layer}_${guard}")
      endif()
      set(guard "HITRAY_LIB_${guard}_H")
      if(NOT text MATCHES "#ifndef ${guard}\n#define ${guard}\n")
        problem("lib/${source}: its include guard is not ${guard}")
      endif()
    endif()
    # A static (or static inline) function named as exported.
    string(REGEX MATCHALL "\n[ \t]*static[^\n;=(]*[ *]hr_[A-Za-z0-9_]+\\(" statics "\n${text}")
    foreach(definition IN LISTS statics)
      string(REGEX MATCH "hr_[A-Za-z0-9_]+\\($" name "${definition}")
      string(REGEX REPLACE "^hr_(.*)\\($" "\\1" bare "${name}")
      problem("lib/${source}: static function hr_${bare}: hr_ names what the library exports; internal is hri_${bare}")
    endforeach()
    # One list element per line: characters that CMake's lists treat
    # specially are dropped first (they never matter to an #include).
    string(REGEX REPLACE "[][;\\\\]" "" text "${text}")
    string(REPLACE "\n" ";" lines "${text}")
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      if(NOT line MATCHES "^([ \t]*#[ \t]*include[ \t]*\")([^\"]+)\"")
        continue()
      endif()
      set(header "${CMAKE_MATCH_2}")
      # The column of the opening quote.
      string(LENGTH "${CMAKE_MATCH_1}" column)
      set(where "lib/${source}:${number}:${column}")
      if(header MATCHES "^([^/]+)/")
        set(folder "${CMAKE_MATCH_1}")
        if(folder STREQUAL layer OR NOT folder IN_LIST lib_folders)
          continue()
        endif()
        if(NOT folder IN_LIST HITRAY_LAYER_USES_${layer})
          problem("${where}: layer ${layer} includes \"${header}\", but ${folder} is not below it (${layer} uses: ${HITRAY_LAYER_USES_${layer}})")
        endif()
      else()
        file(GLOB owners RELATIVE "${LIB_DIR}" "${LIB_DIR}/*/${header}")
        if(owners)
          problem("${where}: \"${header}\" is named without its folder: write \"${owners}\"")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

# --- calls
# Which layer defines each global symbol, and which object does.
set(sym_count 0)
foreach(layer IN LISTS HITRAY_LAYERS)
  set(undefined_${layer} "")
  set(defined_names_${layer} "")
  if(NOT HITRAY_LAYER_OBJECTS_${layer})
    continue()
  endif()
  execute_process(COMMAND "${NM}" -P -A ${HITRAY_LAYER_OBJECTS_${layer}}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${NM} failed on layer ${layer}'s objects: ${err}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    # "<object>: <name> <type> [<value> <size>]"
    if(NOT line MATCHES "^([^:]+): ([A-Za-z_][A-Za-z0-9_.]*) ([A-Za-z])")
      continue()
    endif()
    get_filename_component(object "${CMAKE_MATCH_1}" NAME)
    set(name "${CMAKE_MATCH_2}")
    set(type "${CMAKE_MATCH_3}")
    if(type STREQUAL "U")
      list(APPEND undefined_${layer} "${object}|${name}")
    elseif(type MATCHES "^[A-TV-Z]$")
      set(defined_by_${name} "${layer}")
      list(APPEND defined_names_${layer} "${name}")
      math(EXPR sym_count "${sym_count} + 1")
    endif()
  endforeach()
endforeach()
if(sym_count LESS 50)
  message(FATAL_ERROR "only ${sym_count} symbols defined by the layers' objects: is the manifest ${MANIFEST} right?")
endif()

# The public API: what the library exports.
execute_process(COMMAND "${NM}" -D -P --defined-only "${HITRAY_LIBRARY}"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${NM} failed on ${HITRAY_LIBRARY}: ${err}")
endif()
string(REGEX MATCHALL "(^|\n)hr_[A-Za-z0-9_]+" exported "${out}")
foreach(name IN LISTS exported)
  string(STRIP "${name}" name)
  set(public_${name} TRUE)
endforeach()

# The prefixes: every hr_ symbol a layer defines is exported, every other
# one it shares between files is internal and hri_ (the readers' own sdl_
# and nff_ names are their layer's).
foreach(layer IN LISTS HITRAY_LAYERS)
  foreach(name IN LISTS defined_names_${layer})
    if(name MATCHES "^hr_(.*)" AND NOT public_${name})
      problem("${layer}: ${name} is defined for other files but not exported: an internal name is hri_${CMAKE_MATCH_1}")
    endif()
  endforeach()
endforeach()

set(crossings_seen "")
foreach(layer IN LISTS HITRAY_LAYERS)
  set(calls_${layer} "")
  foreach(ref IN LISTS undefined_${layer})
    string(REPLACE "|" ";" parts "${ref}")
    list(GET parts 0 object)
    list(GET parts 1 name)
    if(NOT DEFINED defined_by_${name})
      continue()
    endif()
    set(callee "${defined_by_${name}}")
    if(callee STREQUAL layer)
      continue()
    endif()
    if("${layer}:${callee}" IN_LIST HITRAY_LAYER_CROSSINGS)
      if(NOT "${layer}:${callee}" IN_LIST crossings_seen)
        list(APPEND crossings_seen "${layer}:${callee}")
      endif()
      message("known crossing (lib/CMakeLists.txt): ${layer}/${object} calls ${name}, defined by layer ${callee}")
      continue()
    endif()
    if(layer IN_LIST HITRAY_CLIENT_LAYERS AND public_${name})
      # Through the public API; the client is above the callee.
    elseif(NOT callee IN_LIST HITRAY_LAYER_USES_${layer})
      problem("${layer}/${object} calls ${name}, defined by layer ${callee}, which is not below ${layer} (${layer} uses: ${HITRAY_LAYER_USES_${layer}})")
    endif()
    if(NOT callee IN_LIST calls_${layer})
      list(APPEND calls_${layer} "${callee}")
      set(example_${layer}_${callee} "${object} calls ${name}")
    endif()
  endforeach()
endforeach()

foreach(crossing IN LISTS HITRAY_LAYER_CROSSINGS)
  if(NOT crossing IN_LIST crossings_seen)
    problem("the crossing ${crossing} listed by hitray_layer_crossing (lib/CMakeLists.txt) no longer occurs: remove it")
  endif()
endforeach()

# --- loops: the layers each one reaches, by USES and by calls
foreach(graph USES CALLS)
  foreach(layer IN LISTS HITRAY_LAYERS)
    if(graph STREQUAL "USES")
      set(reach_${layer} "${HITRAY_LAYER_USES_${layer}}")
    else()
      set(reach_${layer} "${calls_${layer}}")
    endif()
    set(step_${layer} "${reach_${layer}}")
  endforeach()
  set(grown TRUE)
  while(grown)
    set(grown FALSE)
    foreach(layer IN LISTS HITRAY_LAYERS)
      foreach(next IN LISTS reach_${layer})
        foreach(further IN LISTS reach_${next})
          if(NOT further IN_LIST reach_${layer})
            list(APPEND reach_${layer} "${further}")
            set(grown TRUE)
          endif()
        endforeach()
      endforeach()
    endforeach()
  endwhile()
  foreach(layer IN LISTS HITRAY_LAYERS)
    if(NOT layer IN_LIST reach_${layer})
      continue()
    endif()
    # The loop's steps out of this layer, to layers that reach back.
    foreach(next IN LISTS step_${layer})
      if(layer IN_LIST reach_${next} OR next STREQUAL layer)
        if(graph STREQUAL "USES")
          problem("a loop of USES: ${layer} uses ${next}, which reaches back to ${layer}")
        else()
          problem("a loop of calls: ${layer} calls into ${next} (${example_${layer}_${next}}), which calls back to ${layer}")
        endif()
      endif()
    endforeach()
  endforeach()
endforeach()

if(problems GREATER 0)
  message(FATAL_ERROR "layering: ${problems} problem(s): a layer of lib/ reaches up (lib/CMakeLists.txt says what each uses) or a name's prefix is wrong")
endif()
list(LENGTH HITRAY_LAYERS layer_count)
message(STATUS "layering: ${layer_count} layers, ${sym_count} symbols: no include or call reaches up, no loop, hr_ only what is exported")
