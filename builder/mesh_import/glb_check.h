#pragma once
// A binary glTF (.glb) container checked before assimp reads it: assimp 5.2
// reads a file whose header length is larger than the file. This check refuses,
// with the byte offset: a 12-byte header "glTF", version 2, length equal to
// the file's size; then chunks (uint32 length, uint32 type, data), the first of
// type JSON, each inside the file, and nothing after the last chunk (glTF 2.0
// specification, section 4.4; later chunks of any type, as readers must ignore
// unknown ones). The JSON inside is not checked here.
// Errors: "PATH: GLB byte B: reason".
#include <string>
#include <string_view>

#include "shared/error.h"

namespace body {

// `bytes` is the whole file; `path` names it in messages.
Status check_glb_bytes(std::string_view bytes, const std::string& path);
// Reads `path` (regular files only) and checks it.
Status check_glb_file(const std::string& path);

}  // namespace body
