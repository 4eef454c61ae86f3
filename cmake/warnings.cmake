# Warnings are errors for the project's own code; third-party headers come in as SYSTEM.
add_library(body_warnings INTERFACE)
target_compile_options(body_warnings INTERFACE -Wall -Wextra -Wpedantic -Werror
  $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor>)

if(BODY_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()
# libFuzzer steers by coverage of the code under test, not only of the target's
# file: instrument every library (fuzzer-no-link), the targets add the driver.
if(BODY_FUZZ)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
if(BODY_SANITIZE_THREAD)
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()

if(CMAKE_BUILD_TYPE STREQUAL "Debug")
  add_compile_definitions(BODY_GL_DEBUG=1)
endif()

# Same results on x86-64 and aarch64: never fuse a*b+c into an FMA (GCC does on
# aarch64 by default), so meshes and .bpm files are bit-identical across the two
# (the cross smoke compares them).
add_compile_options(-ffp-contract=off)
