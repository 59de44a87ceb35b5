# Helpers shared by the install tests (included by their `cmake -P` scripts).

# Run a command that must succeed; its standard output is left in LAST_OUTPUT.
function(run_checked what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(LAST_OUTPUT "${out}" PARENT_SCOPE)
endfunction()

function(expect_file path)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "not installed: ${path}")
  endif()
endfunction()

# A real PNG: the signature, and more than a header's worth of bytes.
function(expect_png path)
  expect_file("${path}")
  file(READ "${path}" magic LIMIT 8 HEX)
  if(NOT magic STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${path} is not a PNG (starts with ${magic})")
  endif()
  file(SIZE "${path}" size)
  if(size LESS 200)
    message(FATAL_ERROR "${path} is suspiciously small (${size} bytes)")
  endif()
endfunction()

# Install BUILD_DIR into a fresh prefix under WORK_DIR, then move the prefix
# to a path with a space in it: the installed tree must not depend on where
# it was installed, and unquoted paths break. Sets `prefix` in the caller.
function(install_into_moved_prefix)
  file(REMOVE_RECURSE "${WORK_DIR}")
  set(staging "${WORK_DIR}/staging")
  set(moved "${WORK_DIR}/moved prefix")
  run_checked("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${staging}")
  file(RENAME "${staging}" "${moved}")
  set(prefix "${moved}" PARENT_SCOPE)
endfunction()
