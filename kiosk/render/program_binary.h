#pragma once
// Linked programs kept as the driver's binaries (GLES 3.0 glProgramBinary) in a
// directory, so that a kiosk's later starts skip the GLSL front end. Mesa's disk
// cache keeps compiled variants but not parsed shaders: every start compiled each
// program's GLSL again, the first compile also building the built-in function
// library (17 M of the body scene's 108 M instructions before its first frame).
// A file holds its program's whole key (sources and attribute bindings) and is
// used only on an exact match and when the driver accepts the binary (after a
// driver update it refuses them: they are compiled and written again). Best
// effort: nothing read or written here can make a link fail. Off until a
// directory is set (tests, screenshots and benchmarks compile as before).
#include <GLES3/gl3.h>

#include <cstddef>
#include <string>

namespace body::render {

// Where the binaries go (created when first written); empty: off. Process-wide,
// set once before the first link (the kiosk mode does, kiosk/modes/kiosk.cpp).
void set_program_binary_dir(std::string dir);
const std::string& program_binary_dir();
// The kiosk's directory from the environment: beside Mesa's cache
// ($MESA_SHADER_CACHE_DIR/bodyview_programs: the service's /var/cache/bodyview),
// else $XDG_CACHE_HOME/bodyview/programs, else ~/.cache/bodyview/programs;
// empty (off) under MESA_SHADER_CACHE_DISABLE or without any of them.
std::string default_program_binary_dir();

// The program linked from the binary kept for `key`, or 0 (none, another key
// under the same name, refused by the driver, or off).
GLuint load_program_binary(const std::string& key);
// Keeps `program`'s binary for `key` (written atomically; failures ignored).
void save_program_binary(const std::string& key, GLuint program);

// Programs this process has linked from binaries (tests).
size_t program_binaries_loaded();

}  // namespace body::render
