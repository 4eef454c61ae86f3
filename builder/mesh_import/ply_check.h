#pragma once
// A PLY file checked whole before assimp reads it: assimp 5.2 loops for ever
// on a header without end_header, trusts element counts, reads a face list
// longer than its values on into the next rows, and ignores rows that are
// missing or left over. This check refuses, with the place:
//   header  the "ply" magic, a known format, "end_header" within the first
//           64 KiB, known keywords and types, integer element counts that the
//           rest of the file can hold;
//   rows    every element row present with exactly its properties' values
//           (ASCII: one row a line, a list's count equal to the values after
//           it; binary: the rows' bytes), integers within their type, floats
//           finite, list counts not negative, face vertex indices within the
//           vertex element, and nothing after the last row but white space.
// Errors: "PATH: PLY header line N: reason", "PATH: PLY line N (element
// 'E' row R): reason" (ASCII), "PATH: PLY byte B (element 'E' row R):
// reason" (binary). Rows count from 1.
#include <string>
#include <string_view>

#include "shared/error.h"

namespace body {

// `bytes` is the whole file; `path` names it in messages.
Status check_ply_bytes(std::string_view bytes, const std::string& path);
// Reads `path` (regular files only) and checks it.
Status check_ply_file(const std::string& path);

}  // namespace body
