#pragma once
// An STL file checked whole before assimp reads it: assimp 5.2 reads an ASCII
// facet with 2 or 4 vertices, a file without endsolid and anything after it,
// and takes a binary file for ASCII when its 80-byte header begins "solid".
// This check refuses, with the place:
//   binary  a file of exactly 84 + 50 * N bytes, N the header's triangle count
//           (N >= 1), every vertex coordinate a finite float;
//   ASCII   printable text in the grammar solid NAME (facet normal X Y Z
//           outer loop (vertex X Y Z){3} endloop endfacet)* endsolid NAME,
//           one or more solids, numbers finite, at least one facet, nothing
//           else after the last endsolid.
// A file is ASCII when it begins (after white space) with "solid" and holds
// only text; anything else is binary. Errors: "PATH: STL line N: reason"
// (ASCII) or "PATH: STL byte B (triangle T): reason" / "PATH: binary STL
// ...: reason".
#include <string>
#include <string_view>

#include "shared/error.h"

namespace body {

// `bytes` is the whole file; `path` names it in messages.
Status check_stl_bytes(std::string_view bytes, const std::string& path);
// Reads `path` (regular files only) and checks it.
Status check_stl_file(const std::string& path);

}  // namespace body
