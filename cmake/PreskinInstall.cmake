# `cmake --install` in GNUInstallDirs places:
#   lib/libpreskin.so*                      the core library (public API only, hidden internals):
#                                            what a host links; no OpenImageIO, no Embree
#   include/preskin/*.h                      its public headers
#   lib/libpreskin_imageio.so*, include/preskin/imageio/
#                                            component `imageio`: OpenImageIO as an image codec
#                                            (EXR, TIFF in; EXR out), for the tools and hosts that want it
#   lib/libpreskin_reference.so*, include/preskin/DiffusionReference.h, Deformation.h
#                                            component `reference`: the diffusion reference (Embree)
#                                            and the CPU deformation
#   share/preskin/shaders/                   the GLSL include root: preskin/*.glsl (the host library),
#                                            shared/*.h (structs and constants read by C++ and GLSL),
#                                            and the renderer's own entry points (forward.frag, ...)
#   share/preskin/luts/                      the default LUT set and its manifest
#   share/preskin/samples/assets/head/       the sample scene the tools render by default
#   bin/preskin, bin/preskin-viewer          component `tools`: the tools (they find share/preskin
#                                            beside them; they need `imageio` and `reference`)
#   lib/cmake/preskin/                       find_package(preskin CONFIG): preskin::preskin (and
#                                            preskin::imageio, preskin::reference when those
#                                            components are installed), version file
# `cmake --install BUILD --component Unspecified` installs the core alone (library, headers,
# shaders, LUTs, the sample head); without --component every component is installed.
#   lib/pkgconfig/preskin.pc                 pkg-config
include(CMakePackageConfigHelpers)
set(PRESKIN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/preskin)

install(TARGETS preskin EXPORT preskinTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/preskin DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS preskin_imageio EXPORT preskinImageIoTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT imageio NAMELINK_COMPONENT imageio)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/imageio/include/preskin DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  COMPONENT imageio)
install(EXPORT preskinImageIoTargets NAMESPACE preskin:: DESTINATION ${PRESKIN_INSTALL_CMAKEDIR} COMPONENT imageio)
install(TARGETS preskin_reference EXPORT preskinReferenceTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT reference NAMELINK_COMPONENT reference)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/reference/include/preskin DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  COMPONENT reference)
install(EXPORT preskinReferenceTargets NAMESPACE preskin:: DESTINATION ${PRESKIN_INSTALL_CMAKEDIR} COMPONENT reference)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION ${PRESKIN_INSTALL_SHADERDIR}
  FILES_MATCHING PATTERN "*.glsl" PATTERN "*.h" PATTERN "*.vert" PATTERN "*.frag" PATTERN "*.comp")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/luts/ DESTINATION ${PRESKIN_INSTALL_DATADIR}/luts
  FILES_MATCHING PATTERN "manifest.json" PATTERN "*.exr" PATTERN "*.md")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/samples/assets/head DESTINATION ${PRESKIN_INSTALL_DATADIR}/samples/assets
  PATTERN "*.py" EXCLUDE)
install(TARGETS preskin_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
if(TARGET preskin_viewer)
  install(TARGETS preskin_viewer RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT tools)
endif()

install(EXPORT preskinTargets NAMESPACE preskin:: DESTINATION ${PRESKIN_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/preskinConfig.cmake.in
  ${PROJECT_BINARY_DIR}/preskinConfig.cmake
  INSTALL_DESTINATION ${PRESKIN_INSTALL_CMAKEDIR}
  PATH_VARS PRESKIN_INSTALL_SHADERDIR PRESKIN_INSTALL_DATADIR)
# 0.x: minor versions may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/preskinConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/preskinConfig.cmake ${PROJECT_BINARY_DIR}/preskinConfigVersion.cmake
  DESTINATION ${PRESKIN_INSTALL_CMAKEDIR})

# preskin.pc names its prefix relative to its own folder (${pcfiledir}), so it stays right for
# any `cmake --install --prefix` and when the installed tree is moved.
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(PRESKIN_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH pc_to_prefix "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
  string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
  set(PRESKIN_PC_PREFIX "\${pcfiledir}/${pc_to_prefix}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/preskin.pc.in ${PROJECT_BINARY_DIR}/preskin.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/preskin.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
