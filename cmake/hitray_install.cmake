# Installing hitray: the public headers, libhitray.so.0 (with its SONAME),
# a CMake package (find_package(hitray CONFIG) -> hitray::hitray, with a
# version file) and a pkg-config file. Shape modules install themselves
# (hitray_add_shape) and the CLI in cli/CMakeLists.txt.
#
# Every installed path is relative to the prefix, so the tree can be installed
# anywhere (`cmake --install build --prefix DIR`, `make install PREFIX=DIR`)
# and moved afterwards.
include(CMakePackageConfigHelpers)

set(HITRAY_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/hitray)
set(HITRAY_PKGCONFIG_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(TARGETS hitray EXPORT hitrayTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/hitray
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")

install(EXPORT hitrayTargets NAMESPACE hitray:: FILE hitrayTargets.cmake
  DESTINATION ${HITRAY_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/hitrayConfig.cmake.in
  ${PROJECT_BINARY_DIR}/hitrayConfig.cmake
  INSTALL_DESTINATION ${HITRAY_CMAKE_INSTALL_DIR})
# The ABI is that of the SONAME libhitray.so.<major>: any release with the
# same major version serves a program built against an older one.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/hitrayConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/hitrayConfig.cmake ${PROJECT_BINARY_DIR}/hitrayConfigVersion.cmake
  DESTINATION ${HITRAY_CMAKE_INSTALL_DIR})

# pkg-config: the prefix is found from the .pc file's own place
# (${pcfiledir}), so it stays right whatever prefix the tree is installed to.
if(IS_ABSOLUTE "${HITRAY_PKGCONFIG_INSTALL_DIR}")
  set(HITRAY_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH HITRAY_PC_UP "/prefix/${HITRAY_PKGCONFIG_INSTALL_DIR}" "/prefix")
  string(REGEX REPLACE "/$" "" HITRAY_PC_UP "${HITRAY_PC_UP}")
  set(HITRAY_PC_PREFIX "\${pcfiledir}/${HITRAY_PC_UP}")
endif()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(HITRAY_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(HITRAY_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/cmake/hitray.pc.in ${PROJECT_BINARY_DIR}/hitray.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/hitray.pc DESTINATION ${HITRAY_PKGCONFIG_INSTALL_DIR})

# What a reader of the man page is pointed to: the docs (the scene language
# in sdl.md among them) and the example scenes, beside each other.
set(HITRAY_DATA_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/hitray)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${HITRAY_DATA_INSTALL_DIR}/docs)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${HITRAY_DATA_INSTALL_DIR}/scenes)
