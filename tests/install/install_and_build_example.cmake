# Install the build tree into a fresh prefix, move the prefix elsewhere (the
# installed tree must not depend on where it was installed), then build
# examples/c against it as a user would and run the result:
#   MODE=cmake      find_package(hitray CONFIG) and hitray::hitray
#   MODE=pkgconfig  cc spheres.c $(pkg-config --cflags --libs hitray)
# Variables: MODE BUILD_DIR SOURCE_DIR WORK_DIR LIBDIR GENERATOR C_COMPILER
#            EXTRA_FLAGS (sanitizer flags of the build, may be empty) VERSION
#            VIEW (ON when hitray-view is built)
cmake_minimum_required(VERSION 3.18)

include(${CMAKE_CURRENT_LIST_DIR}/install_common.cmake)

install_into_moved_prefix()

# The layout the package promises.
expect_file("${prefix}/include/hitray/hitray.h")
expect_file("${prefix}/include/hitray/shape_module.h")
expect_file("${prefix}/include/hitray/shape_kit.h")
expect_file("${prefix}/${LIBDIR}/libhitray.so.0")
expect_file("${prefix}/${LIBDIR}/libhitray.so")
expect_file("${prefix}/${LIBDIR}/hitray/shapes/sphere.so")
expect_file("${prefix}/${LIBDIR}/cmake/hitray/hitrayConfig.cmake")
expect_file("${prefix}/${LIBDIR}/cmake/hitray/hitrayConfigVersion.cmake")
expect_file("${prefix}/${LIBDIR}/pkgconfig/hitray.pc")
expect_file("${prefix}/bin/hitray")
expect_file("${prefix}/share/man/man1/hitray.1")
expect_file("${prefix}/share/hitray/docs/sdl.md")
expect_file("${prefix}/share/hitray/scenes/demo.sdl")

# The installed command runs from its new place and finds the installed
# library and shape modules through relative paths alone.
run_checked("installed hitray --version" "${prefix}/bin/hitray" --version)
if(NOT LAST_OUTPUT MATCHES "hitray ${VERSION}")
  message(FATAL_ERROR "unexpected version output: ${LAST_OUTPUT}")
endif()
run_checked("installed hitray shapes" "${prefix}/bin/hitray" shapes)
if(NOT LAST_OUTPUT MATCHES "moved prefix/[^\n]*hitray/shapes/sphere\\.so")
  message(FATAL_ERROR "the installed hitray did not find the installed modules:\n${LAST_OUTPUT}")
endif()
# `hitray view` runs the hitray-view installed beside it (its --help needs
# no display).
if(VIEW)
  expect_file("${prefix}/bin/hitray-view")
  run_checked("installed hitray view --help" "${prefix}/bin/hitray" view --help)
  if(NOT LAST_OUTPUT MATCHES "usage: hitray view SCENE")
    message(FATAL_ERROR "the installed hitray view did not run hitray-view:\n${LAST_OUTPUT}")
  endif()
endif()

# The installed example scene renders with the installed command.
run_checked("installed hitray render of the installed demo scene" "${prefix}/bin/hitray" render
  "${prefix}/share/hitray/scenes/demo.sdl" -o "${WORK_DIR}/demo.png" --size 32x24)
expect_png("${WORK_DIR}/demo.png")

set(image "${WORK_DIR}/spheres.png")
if(MODE STREQUAL "cmake")
  run_checked("configuring examples/c" "${CMAKE_COMMAND}" -S "${SOURCE_DIR}/examples/c" -B "${WORK_DIR}/example"
    -G "${GENERATOR}" "-DCMAKE_C_COMPILER=${C_COMPILER}" "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_C_FLAGS=${EXTRA_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXTRA_FLAGS}")
  run_checked("building examples/c" "${CMAKE_COMMAND}" --build "${WORK_DIR}/example")
  run_checked("running the example" "${WORK_DIR}/example/spheres" "${image}" 64x48)
elseif(MODE STREQUAL "pkgconfig")
  find_program(PKG_CONFIG pkg-config REQUIRED)
  set(ENV{PKG_CONFIG_PATH} "${prefix}/${LIBDIR}/pkgconfig")
  run_checked("pkg-config --modversion" "${PKG_CONFIG}" --modversion hitray)
  string(STRIP "${LAST_OUTPUT}" version)
  if(NOT version STREQUAL VERSION)
    message(FATAL_ERROR "pkg-config says version ${version}, expected ${VERSION}")
  endif()
  run_checked("pkg-config --cflags --libs" "${PKG_CONFIG}" --cflags --libs hitray)
  string(STRIP "${LAST_OUTPUT}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  separate_arguments(extra UNIX_COMMAND "${EXTRA_FLAGS}")
  # The same thing a user types: cc spheres.c $(pkg-config --cflags --libs hitray).
  # What the README says of a prefix the loader does not search: linked with
  # the flags alone, the program cannot find libhitray.so.0 when it starts;
  # LD_LIBRARY_PATH or an RPATH to the prefix's libdir lets it.
  run_checked("compiling with pkg-config flags alone" "${C_COMPILER}" -std=c11 -Wall -Werror ${extra}
    "${SOURCE_DIR}/examples/c/spheres.c" -o "${WORK_DIR}/spheres-no-rpath" ${flags})
  execute_process(COMMAND "${WORK_DIR}/spheres-no-rpath" "${image}" 64x48
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0 OR NOT err MATCHES "libhitray\\.so\\.0")
    message(FATAL_ERROR "without an RPATH the example was expected not to find libhitray.so.0 "
      "(${rc}):\n${out}\n${err}")
  endif()
  set(ENV{LD_LIBRARY_PATH} "${prefix}/${LIBDIR}")
  run_checked("running the example with LD_LIBRARY_PATH" "${WORK_DIR}/spheres-no-rpath" "${image}" 64x48)
  unset(ENV{LD_LIBRARY_PATH})
  run_checked("pkg-config --variable=libdir" "${PKG_CONFIG}" --variable=libdir hitray)
  string(STRIP "${LAST_OUTPUT}" libdir)
  string(REPLACE "\\ " " " libdir "${libdir}")  # pkg-config escapes the prefix's space
  run_checked("compiling with pkg-config flags and an RPATH" "${C_COMPILER}" -std=c11 -Wall -Werror ${extra}
    "${SOURCE_DIR}/examples/c/spheres.c" -o "${WORK_DIR}/spheres" ${flags} "-Wl,-rpath,${libdir}")
  run_checked("running the example" "${WORK_DIR}/spheres" "${image}" 64x48)
else()
  message(FATAL_ERROR "unknown MODE '${MODE}'")
endif()
expect_png("${image}")
message(STATUS "installed, built with ${MODE}, ran: ${image}")
