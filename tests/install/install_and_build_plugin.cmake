# Install the build tree into a fresh prefix, build examples/shape_plugin (a
# shape module written outside hitray's tree, and a driver using it) against
# it as a user would, and check that the *installed* hitray and library load
# the plugin from HITRAY_SHAPE_PATH and use it:
#   - the module links nothing of libhitray and exports its entry point;
#   - `hitray shapes` lists the disk class and its radius parameter;
#   - the first hit of hand-computed rays (from above, slanted, from below,
#     the rim, outside the rim, parallel) is exactly the expected one;
#   - a radius the plugin refuses (0, -0) and one the host refuses by the
#     declared range (2e6) exit 1 with a message naming `radius`;
#   - a render of the example scene writes a PNG;
#   - copied into <prefix>/lib/hitray/shapes, the module is found with no
#     HITRAY_SHAPE_PATH at all.
# Variables: BUILD_DIR SOURCE_DIR WORK_DIR LIBDIR GENERATOR C_COMPILER
#            EXTRA_FLAGS (sanitizer flags of the build, may be empty) READELF NM
cmake_minimum_required(VERSION 3.18)

include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

# Run a command that must fail with exit status 1 and a message on stderr
# matching `pattern`.
function(run_refused what pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 1)
    message(FATAL_ERROR "${what}: expected exit status 1, got ${rc}:\n${ARGN}\n${out}\n${err}")
  endif()
  if(NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "${what}: the message does not match '${pattern}':\n${err}")
  endif()
endfunction()

install_into_moved_prefix()
set(hitray "${prefix}/bin/hitray")

# Build the plugin as a user would. -Werror with the example's own -Wall
# -Wextra: the example must stay warning-free.
set(plugin_build "${WORK_DIR}/plugin build")
run_checked("configuring examples/shape_plugin" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/examples/shape_plugin"
  -B "${plugin_build}" -G "${GENERATOR}" "-DCMAKE_C_COMPILER=${C_COMPILER}" "-DCMAKE_PREFIX_PATH=${prefix}"
  "-DCMAKE_C_FLAGS=${EXTRA_FLAGS} -Werror" "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}"
  "-DCMAKE_MODULE_LINKER_FLAGS=${EXTRA_FLAGS}")
run_checked("building examples/shape_plugin" "${CMAKE_COMMAND}" --build "${plugin_build}")
set(module "${plugin_build}/disk.so")
set(demo "${plugin_build}/disk_demo")
if(NOT EXISTS "${module}")
  message(FATAL_ERROR "the plugin was not built as ${module} (no lib prefix)")
endif()

# A module gets everything from the host table: it must not need libhitray,
# and it must export the entry point the host looks up.
run_checked("readelf -d disk.so" "${READELF}" -d "${module}")
if(LAST_OUTPUT MATCHES "\\(NEEDED\\)[^\n]*libhitray")
  message(FATAL_ERROR "disk.so links libhitray; a module must not:\n${LAST_OUTPUT}")
endif()
run_checked("nm -D disk.so" "${NM}" -D --defined-only "${module}")
if(NOT LAST_OUTPUT MATCHES "[0-9a-fA-F]+ T hr_shape_module\n")
  message(FATAL_ERROR "disk.so does not export hr_shape_module:\n${LAST_OUTPUT}")
endif()

# The installed command finds the plugin through HITRAY_SHAPE_PATH.
set(ENV{HITRAY_SHAPE_PATH} "${plugin_build}")
run_checked("installed hitray shapes" "${hitray}" shapes)
string(FIND "${LAST_OUTPUT}" "${module}\n  module disk: " at)
if(at LESS 0 OR NOT LAST_OUTPUT MATCHES "\n  disk - [^\n]*\n +radius +number +default 1 range \\(0, 1e\\+06\\]")
  message(FATAL_ERROR "hitray shapes does not list the disk plugin (${module}) as expected:\n${LAST_OUTPUT}")
endif()
# The module's metadata (hr_module_info.version, author), as disk.c gives it.
if(NOT LAST_OUTPUT MATCHES "module disk: [^\n]*\n  version 1\\.0\\.0, by the hitray authors")
  message(FATAL_ERROR "hitray shapes does not show the disk plugin's version and author:\n${LAST_OUTPUT}")
endif()
if(LAST_OUTPUT MATCHES "NOT LOADED")
  message(FATAL_ERROR "hitray shapes reports a module it could not load:\n${LAST_OUTPUT}")
endif()

# First hits worked out by hand; every value is exact in binary, so the
# output (17 significant digits) must match exactly. The disk is
# x^2 + y^2 <= r^2 in z = 0, normal +z, the scene's only object, untransformed.
function(expect_hit radius origin dir expected)
  run_checked("disk_demo ${radius} hit ${origin} ${dir}" "${demo}" ${radius} hit ${origin} ${dir})
  string(STRIP "${LAST_OUTPUT}" got)
  if(NOT got STREQUAL expected)
    message(FATAL_ERROR "disk_demo ${radius} hit ${origin} ${dir}:\n  expected: ${expected}\n  got:      ${got}")
  endif()
endfunction()
# From above, straight down: z = 4 - 2t = 0 at t = 2; moving against the normal enters.
expect_hit(2 1,1,4 0,0,-2 "t 2 point 1 1 0 normal 0 0 1 entering 1")
# Slanted: z = 2 - t = 0 at t = 2, point (3 - 2, 0 + 1, 0).
expect_hit(2 3,0,2 -1,0.5,-1 "t 2 point 1 1 0 normal 0 0 1 entering 1")
# From below: moving along the normal leaves.
expect_hit(2 0,0,-1 0,0,1 "t 1 point 0 0 0 normal 0 0 1 entering 0")
# On the rim, which belongs to the disk: |(2, 0)| = 2 = r.
expect_hit(2 2,0,1 0,0,-1 "t 1 point 2 0 0 normal 0 0 1 entering 1")
# Just outside the rim: |(1.5, 1.5)| = 2.12 > 2; inside for r = 3.
expect_hit(2 1.5,1.5,1 0,0,-1 "no hit")
expect_hit(3 1.5,1.5,1 0,0,-1 "t 1 point 1.5 1.5 0 normal 0 0 1 entering 1")
# In the plane of the disk: parallel, seen edge-on, no hit (and no NaN).
expect_hit(2 -5,0,0 1,0,0 "no hit")
# The plane is crossed behind the origin (t = -1): not a hit for t > 0.
expect_hit(2 0,0,1 0,0,1 "no hit")

# Refusals name the parameter, all by the host's range check: (0, 1e6]
# excludes 0 and -0 and stops at 1e6.
run_refused("radius 0" "shape 'disk' \\(module '[^']*disk\\.so'\\): parameter 'radius' = 0 is outside \\(0, 1e\\+06\\]: it must be > 0"
  "${demo}" 0 hit 0,0,1 0,0,-1)
run_refused("radius -0" "parameter 'radius' = -0 is outside \\(0, 1e\\+06\\]: it must be > 0" "${demo}" -0 hit 0,0,1 0,0,-1)
run_refused("radius 2e6" "parameter 'radius' = 2e\\+06 is outside \\(0, 1e\\+06\\]" "${demo}" 2e6 hit 0,0,1 0,0,-1)

# The example scene renders.
set(image "${WORK_DIR}/disk.png")
run_checked("disk_demo render" "${demo}" 1.5 render "${image}" 64x48)
expect_png("${image}")

# From SDL: a module's class is an object keyword followed by its parameters.
# The installed hitray renders the example scene and traces it: the disk of
# radius 2.5 turned to face +y; a ray down from (1, 5, 1) meets it at t = 5.
set(sdl_image "${WORK_DIR}/disk_sdl.png")
run_checked("hitray render disk.sdl" "${hitray}" render "${SOURCE_DIR}/examples/shape_plugin/disk.sdl"
  -o "${sdl_image}" --size 64x48)
expect_png("${sdl_image}")
run_checked("hitray hits disk.sdl" "${hitray}" hits "${SOURCE_DIR}/examples/shape_plugin/disk.sdl"
  --origin 1,5,1 --dir 0,-1,0)
string(FIND "${LAST_OUTPUT}"
  "{\"t\": 5.0, \"point\": [1.0, 0.0, 1.0], \"normal\": [0.0, 1.0, 0.0], \"entering\": true, \"surface\": 0, \"object\": 0, \"shape\": \"disk\"}"
  at)
if(at LESS 0)
  message(FATAL_ERROR "hitray hits on disk.sdl: unexpected output:\n${LAST_OUTPUT}")
endif()

# The other way to install a plugin: copy it next to the built-in shapes.
unset(ENV{HITRAY_SHAPE_PATH})
file(COPY "${module}" DESTINATION "${prefix}/${LIBDIR}/hitray/shapes")
run_checked("installed hitray shapes, plugin copied into the prefix" "${hitray}" shapes)
if(NOT LAST_OUTPUT MATCHES "moved prefix/[^\n]*hitray/shapes/disk\\.so\n  module disk")
  message(FATAL_ERROR "hitray did not find disk.so copied into its shapes directory:\n${LAST_OUTPUT}")
endif()
expect_hit(2 1,1,4 0,0,-2 "t 2 point 1 1 0 normal 0 0 1 entering 1")
message(STATUS "plugin built against the installed hitray, listed, traced and rendered: ${image}")
