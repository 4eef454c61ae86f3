# Install layout and .deb packages (a museum installs a .deb on the board).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/kiosk/shaders/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyview/shaders
        OPTIONAL FILES_MATCHING PATTERN "*.glsl" PATTERN "*.vert" PATTERN "*.frag")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/samples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodygen/samples OPTIONAL)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME bodygen)
set(CPACK_PACKAGE_VENDOR "BodyGen project")
set(CPACK_PACKAGE_CONTACT "BodyGen maintainers <maintainers@bodygen.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
if(NOT CPACK_DEBIAN_PACKAGE_ARCHITECTURE)
  if(CMAKE_SYSTEM_PROCESSOR MATCHES "aarch64|arm64")
    set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
  else()
    set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE amd64)
  endif()
endif()
# Runtime libraries by package name (dpkg-shlibdeps cannot run for a foreign architecture).
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6, libstdc++6, libegl1, libgles2, libglfw3, libgbm1, libdrm2, libevdev2, fonts-dejavu-core, libegl-mesa0, libgl1-mesa-dri")
if(BODY_WITH_IMPORT)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libniftiio2, libznz3, libdcmtk17")
endif()
include(CPack)
