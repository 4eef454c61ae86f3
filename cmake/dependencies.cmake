# Every dependency is a Debian package installed by setup.sh.
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(glm REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(meshoptimizer REQUIRED)
find_package(tinyobjloader REQUIRED)

pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(GLESV2 REQUIRED IMPORTED_TARGET glesv2)
pkg_check_modules(EVDEV REQUIRED IMPORTED_TARGET libevdev)
# Clipper: polygon unions for contour repair (builder/contours/repair.cpp).
pkg_check_modules(POLYCLIPPING REQUIRED IMPORTED_TARGET polyclipping)
if(BODY_WITH_GLFW)
  pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET glfw3)
endif()
if(BODY_WITH_DRM)
  pkg_check_modules(DRM REQUIRED IMPORTED_TARGET libdrm)
  pkg_check_modules(GBM REQUIRED IMPORTED_TARGET gbm)
endif()
# Optional, for the kiosk as a service (platform/service_notify.h, seat_* and
# input hotplug): each missing one leaves a fallback, named here.
pkg_check_modules(SYSTEMD QUIET IMPORTED_TARGET libsystemd)
if(NOT SYSTEMD_FOUND)
  message(STATUS "libsystemd not found (libsystemd-dev): service notifications use bodyview's own sd_notify datagram")
endif()
pkg_check_modules(SEAT QUIET IMPORTED_TARGET libseat)
if(NOT SEAT_FOUND)
  message(STATUS "libseat not found (libseat-dev): bodyview opens display and input devices directly (root or "
                 "members of video and input), without VT switching")
endif()
pkg_check_modules(UDEV QUIET IMPORTED_TARGET libudev)
if(NOT UDEV_FOUND)
  message(STATUS "libudev not found (libudev-dev): the DRM backend does not notice a display plugged in at run time")
endif()

# Text for every script in the kiosk (kiosk/app/text_shaping.cpp): HarfBuzz
# shapes, FriBidi orders right-to-left text, ICU finds line breaks (UAX #14).
pkg_check_modules(HARFBUZZ REQUIRED IMPORTED_TARGET harfbuzz)
pkg_check_modules(FRIBIDI REQUIRED IMPORTED_TARGET fribidi)
pkg_check_modules(ICU_UC REQUIRED IMPORTED_TARGET icu-uc)

# stb (header-only here) and the DejaVu font.
find_path(STB_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb REQUIRED)
add_library(body_stb INTERFACE)
target_include_directories(body_stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})
set(BODY_FONT_FILE /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf CACHE FILEPATH "UI font")

# glTF export (tinygltf, header-only; Debian ships it for the host only): optional.
find_path(TINYGLTF_INCLUDE_DIR tiny_gltf.h)
# STL/PLY/glTF import (Open Asset Import, Debian libassimp-dev): optional, host
# builds only (the cross build lists no assimp:arm64).
if(NOT CMAKE_CROSSCOMPILING)
  find_package(assimp QUIET)
endif()

if(BODY_WITH_IMPORT)
  find_path(NIFTI_INCLUDE_DIR nifti1_io.h PATH_SUFFIXES nifti REQUIRED)
  find_library(NIFTI_LIBRARY niftiio REQUIRED)
  find_library(ZNZ_LIBRARY znz REQUIRED)
  find_package(ZLIB REQUIRED)
  find_package(DCMTK REQUIRED)
endif()

if(BODY_BUILD_TESTS)
  find_package(GTest REQUIRED)
  include(GoogleTest)
endif()
if(BODY_BUILD_BENCH)
  find_package(benchmark QUIET)
endif()
