# hitray_add_shape(<name> SOURCES <files...>)
# Builds one loadable shape module, <name>.so, into the build tree's
# lib/hitray/shapes and installs it under lib/hitray/shapes. A module links
# nothing of libhitray: it sees only the public headers.
function(hitray_add_shape name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_library(shape_${name} MODULE ${ARG_SOURCES})
  target_include_directories(shape_${name} PRIVATE ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(shape_${name} PRIVATE m ${ARG_LIBS})
  set_target_properties(shape_${name} PROPERTIES
    PREFIX "" OUTPUT_NAME ${name}
    LIBRARY_OUTPUT_DIRECTORY ${HITRAY_SHAPE_OUTPUT_DIR})
  install(TARGETS shape_${name} LIBRARY DESTINATION ${HITRAY_SHAPE_INSTALL_DIR})
  set_property(GLOBAL APPEND PROPERTY HITRAY_SHAPE_TARGETS shape_${name})
endfunction()

# hitray_add_test_library(<name> SOURCES <files...> [LIBS <libs...>])
# Support code shared by several tests (a scene builder, the module host,
# ...) as a static library, so each source compiles once per build tree
# rather than once per test that lists it. It sees what a test sees (the
# public headers, tests/support, the HR_TEST_* paths) and hands its own
# folder's headers and its LIBS on to the tests that link it.
function(hitray_add_test_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(${name} PRIVATE
    HR_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    HR_TEST_BINARY_DIR="${PROJECT_BINARY_DIR}"
    HR_TEST_SHAPE_DIR="${HITRAY_SHAPE_OUTPUT_DIR}")
  target_link_libraries(${name} PUBLIC hitray_test_support ${ARG_LIBS})
endfunction()

# hitray_add_c_test(<name> SOURCES <files...> [LIBS <libs...>] [ARGS <args...>])
# A C test program run by ctest (with ARGS, none by default); it knows the source and
# build trees through HR_TEST_SOURCE_DIR and HR_TEST_BINARY_DIR. Every test
# depends on every shape module, so ctest never runs against stale modules.
function(hitray_add_c_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS;ARGS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/include
                             ${PROJECT_SOURCE_DIR}/tests/support)
  target_compile_definitions(${name} PRIVATE
    HR_TEST_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    HR_TEST_BINARY_DIR="${PROJECT_BINARY_DIR}"
    HR_TEST_SHAPE_DIR="${HITRAY_SHAPE_OUTPUT_DIR}")
  target_link_libraries(${name} PRIVATE hitray_test_support ${ARG_LIBS} m)
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
  get_property(shape_targets GLOBAL PROPERTY HITRAY_SHAPE_TARGETS)
  if(shape_targets)
    add_dependencies(${name} ${shape_targets})
  endif()
  add_test(NAME ${name} COMMAND ${name} ${ARG_ARGS})
  # Labels (tests/CMakeLists.txt lists which tests get which): the test's
  # folder (core, sdl, shapes, ...), and what the Makefile picks by.
  get_filename_component(area ${CMAKE_CURRENT_SOURCE_DIR} NAME)
  set(labels ${area})
  foreach(label memcheck threads slow)
    string(TOUPPER ${label} list)
    if(name IN_LIST HR_${list}_TESTS)
      list(APPEND labels ${label})
    endif()
  endforeach()
  set_property(TEST ${name} APPEND PROPERTY LABELS ${labels})
endfunction()
