# The layering check fails, naming the crossing, on each crossing planted in a
# copy: an upward include, a bare one and a stale include guard (in a copy
# of lib/'s sources), an upward call and a loop of calls (in a copy of the
# manifest, with the trace layer's shade.c object filed in a lower layer),
# a tolerated crossing that no longer occurs, and the prefixes broken: a
# static hr_ function (in the copy) and an hr_ symbol that is not exported
# (an object compiled here, filed in util).
# Variables: LIB_DIR MANIFEST NM CHECK WORK_DIR CC
cmake_minimum_required(VERSION 3.18)

# run_check(<lib dir> <manifest> <regex>...): the check fails, and its output
# matches every regex.
function(run_check lib manifest)
  execute_process(COMMAND "${CMAKE_COMMAND}" -DLIB_DIR=${lib} -DMANIFEST=${manifest} -DNM=${NM} -P "${CHECK}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(rc EQUAL 0)
    message(FATAL_ERROR "the layering check passed on ${lib} with ${manifest}, which has a planted crossing:\n${out}")
  endif()
  foreach(expected IN LISTS ARGN)
    if(NOT out MATCHES "${expected}")
      message(FATAL_ERROR "the layering check's output lacks \"${expected}\":\n${out}")
    endif()
  endforeach()
  message(STATUS "caught: ${ARGN}")
endfunction()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
file(COPY "${LIB_DIR}/" DESTINATION "${WORK_DIR}/lib")
set(copy "${WORK_DIR}/lib")

# util/strutil.c including a header of scene, above it: the line is the file's
# last, so its number is the count of lines after the append.
file(APPEND "${copy}/util/strutil.c" "#include \"scene/scene_internal.h\"\n")
file(READ "${copy}/util/strutil.c" text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines last)
run_check("${copy}" "${MANIFEST}"
  "lib/util/strutil\\.c:${last}:10: layer util includes \"scene/scene_internal\\.h\", but scene is not below it")
file(COPY "${LIB_DIR}/util/strutil.c" DESTINATION "${copy}/util")

# A header of lib/ named bare, so no folder shows at the include.
file(APPEND "${copy}/geometry/camera.c" "#include \"texture.h\"\n")
run_check("${copy}" "${MANIFEST}" "lib/geometry/camera\\.c:[0-9]+:10: \"texture\\.h\" is named without its folder: write \"texture/texture\\.h\"")
file(COPY "${LIB_DIR}/geometry/camera.c" DESTINATION "${copy}/geometry")

# A header moved without its guard renamed.
file(RENAME "${copy}/util/suggest.h" "${copy}/core/suggest.h")
run_check("${copy}" "${MANIFEST}" "lib/core/suggest\\.h: its include guard is not HITRAY_LIB_CORE_SUGGEST_H")
file(RENAME "${copy}/core/suggest.h" "${copy}/util/suggest.h")

# A static function with the exported prefix.
file(APPEND "${copy}/util/strutil.h" "static inline int hr_planted_inline(void) { return 0; }\n")
run_check("${copy}" "${MANIFEST}"
  "lib/util/strutil\\.h: static function hr_planted_inline: hr_ names what the library exports; internal is hri_planted_inline")
file(COPY "${LIB_DIR}/util/strutil.h" DESTINATION "${copy}/util")

include("${MANIFEST}")
set(shade "")
foreach(object IN LISTS HITRAY_LAYER_OBJECTS_trace)
  if(object MATCHES "/shade\\.c\\.o(bj)?$")
    set(shade "${object}")
  endif()
endforeach()
if(NOT shade)
  message(FATAL_ERROR "no shade.c object among the trace layer's: ${HITRAY_LAYER_OBJECTS_trace}")
endif()
file(READ "${MANIFEST}" manifest)

# shade.c (it calls hri_scene_trace_first) filed in util, which uses no trace.
string(APPEND manifest "list(APPEND HITRAY_LAYER_OBJECTS_util \"${shade}\")\n")
file(WRITE "${WORK_DIR}/upward_call.cmake" "${manifest}")
run_check("${LIB_DIR}" "${WORK_DIR}/upward_call.cmake"
  "util/shade\\.c\\.o calls hri_scene_trace_first, defined by layer trace, which is not below util")

# shade.c filed in texture too, allowed to use trace: texture calls trace
# (hri_scene_trace_first), which calls texture (hri_texture_color).
file(READ "${MANIFEST}" manifest)
string(APPEND manifest "list(APPEND HITRAY_LAYER_OBJECTS_texture \"${shade}\")\n"
                       "list(APPEND HITRAY_LAYER_USES_texture trace)\n")
file(WRITE "${WORK_DIR}/loop.cmake" "${manifest}")
run_check("${LIB_DIR}" "${WORK_DIR}/loop.cmake"
  "a loop of USES: texture uses trace"
  "a loop of calls: texture calls into trace \\(shade\\.c\\.o calls [a-z_]+\\), which calls back to texture")

# A tolerated crossing that no longer occurs is to be struck from the list.
file(READ "${MANIFEST}" manifest)
string(APPEND manifest "list(APPEND HITRAY_LAYER_CROSSINGS geometry:render)\n")
file(WRITE "${WORK_DIR}/stale_crossing.cmake" "${manifest}")
run_check("${LIB_DIR}" "${WORK_DIR}/stale_crossing.cmake"
  "the crossing geometry:render listed by hitray_layer_crossing \\(lib/CMakeLists\\.txt\\) no longer occurs")

# An hr_ function defined for other files but not exported.
file(WRITE "${WORK_DIR}/planted.c" "int hr_planted_internal(void);\nint hr_planted_internal(void) { return 1; }\n")
execute_process(COMMAND "${CC}" -c "${WORK_DIR}/planted.c" -o "${WORK_DIR}/planted.o"
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${CC} could not compile the planted object: ${err}")
endif()
file(READ "${MANIFEST}" manifest)
string(APPEND manifest "list(APPEND HITRAY_LAYER_OBJECTS_util \"${WORK_DIR}/planted.o\")\n")
file(WRITE "${WORK_DIR}/unexported.cmake" "${manifest}")
run_check("${LIB_DIR}" "${WORK_DIR}/unexported.cmake"
  "util: hr_planted_internal is defined for other files but not exported: an internal name is hri_planted_internal")
