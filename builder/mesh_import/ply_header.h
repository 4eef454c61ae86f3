#pragma once
// A PLY file's header checked before assimp reads it (assimp 5.2 loops for
// ever on a header without end_header, and trusts element counts): the
// "ply" magic, a known format, "end_header" within the first 64 KiB, element
// counts that are integers and that the rest of the file can hold (at least
// 2 bytes a row in ASCII, the fixed-size properties' bytes a row in binary).
// Errors name the file and the header line.
#include <string>

#include "shared/error.h"

namespace body {

Status check_ply_header(const std::string& path);

}  // namespace body
