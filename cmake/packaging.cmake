# Install layout and .deb packages (a museum installs a .deb on the board).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/kiosk/shaders/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyview/shaders
        OPTIONAL FILES_MATCHING PATTERN "*.glsl" PATTERN "*.vert" PATTERN "*.frag")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/samples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodygen/samples OPTIONAL)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR} OPTIONAL)

# The kiosk as a service (packaging/): the systemd unit (not enabled by the
# package), its user (sysusers.d), the configuration (a conffile) and a sample
# exhibit: the AAL brain bundle where scripts/build-sample.sh has made it in
# this build tree, else a one-model placeholder.
install(FILES ${PROJECT_SOURCE_DIR}/packaging/systemd/bodyview.service DESTINATION lib/systemd/system)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/systemd/bodyview.sysusers DESTINATION lib/sysusers.d
        RENAME bodyview.conf)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/bodyview.conf DESTINATION /etc/bodyview)
install(FILES ${PROJECT_SOURCE_DIR}/packaging/exhibit/scene.json DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyview/exhibit)
install(FILES ${PROJECT_SOURCE_DIR}/tests/data/models/smoke.obj DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyview/exhibit
        RENAME sample.obj)
install(DIRECTORY ${PROJECT_BINARY_DIR}/sample/bundle/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bodyview/exhibit OPTIONAL)

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
# Every NEEDED library's package (scripts/check-deb-depends.sh checks that
# against the binaries; Debian 12 package names).
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6, libstdc++6, libgcc-s1, libegl1, libgles2, libglfw3, libgbm1, libdrm2, libevdev2, fonts-dejavu-core, libegl-mesa0, libgl1-mesa-dri, libmeshoptimizer2d, libtinyobjloader2rc10, libpolyclipping22, libharfbuzz0b, libfribidi0, libicu72")
if(SYSTEMD_FOUND)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libsystemd0")
endif()
if(SEAT_FOUND)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libseat1")
endif()
if(UDEV_FOUND)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libudev1")
endif()
if(BODY_WITH_IMPORT)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libniftiio2, libznz3, libdcmtk17, zlib1g")
endif()
if(TARGET assimp::assimp)
  string(APPEND CPACK_DEBIAN_PACKAGE_DEPENDS ", libassimp5")
endif()
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/packaging/debian/postinst ${PROJECT_SOURCE_DIR}/packaging/debian/prerm
    ${PROJECT_SOURCE_DIR}/packaging/debian/postrm ${PROJECT_SOURCE_DIR}/packaging/debian/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# adduser: the postinst's fallback where systemd-sysusers is absent.
# fonts-noto-core, fonts-noto-cjk: the kiosk's Arabic, Hebrew and CJK fallback fonts.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "systemd, adduser, fonts-noto-core, fonts-noto-cjk")
# seatd: the seat manager where logind is not running.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "seatd")
include(CPack)
