# Cross-compiling for 64-bit ARM boards (Raspberry Pi 4/5 class) with Debian's
# aarch64-linux-gnu toolchain and multiarch :arm64 libraries. Tests run under
# qemu-aarch64 through CMAKE_CROSSCOMPILING_EMULATOR, so `ctest` works as is.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Multiarch: target libraries live in /usr/lib/aarch64-linux-gnu; headers are shared in /usr/include.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu /usr)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")

# `-L /`, not `-L /usr/aarch64-linux-gnu`: the loader must come from the same
# glibc build as the multiarch libc6:arm64 it loads. The cross package's
# ld-linux (2.36-8cross1) with multiarch libc.so (2.36-9+deb12u*) hangs in the
# first pthread_create.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64;-L;/)
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
