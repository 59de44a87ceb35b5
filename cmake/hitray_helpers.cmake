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
  if(name IN_LIST HR_MEMCHECK_TESTS)
    set_property(TEST ${name} APPEND PROPERTY LABELS memcheck)
  endif()
endfunction()
