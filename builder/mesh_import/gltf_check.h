#pragma once
// A glTF 2.0 asset (.gltf, or a .glb after check_glb_bytes) checked before
// assimp reads it: assimp 5.2 drops a face whose index is past the vertices
// and reads the rest. Parsed with tinygltf (external buffers: regular files
// next to the asset only), then refused, with the place:
//   bufferView  inside its buffer (byteOffset + byteLength);
//   accessor    not sparse, known component type and type, count >= 1, a
//               stride of at least one element and a multiple of the
//               component size, offset + (count - 1) x stride + element
//               size inside its bufferView;
//   primitive   mode triangles, strip or fan (points and lines are no
//               surface); POSITION present, VEC3 of float, every value
//               finite; every attribute's count equal to POSITION's;
//               indices SCALAR of unsigned byte/short/int, each below the
//               POSITION count; a triangle list's count a multiple of 3.
// Errors: "PATH: glTF: reason" (tinygltf's parse), "PATH: glTF bufferView
// V: reason", "PATH: glTF accessor A: reason", "PATH: glTF mesh M
// primitive P [accessor A (SEMANTIC) [element E]]: reason". Indices from 0.
// Without tinygltf (BODY_WITH_GLTF unset) every asset passes.
#include <string>
#include <string_view>

#include "shared/error.h"

namespace body {

// `bytes` is the whole file (GLB container when `binary`); external buffer
// URIs resolve against `base_dir`; `path` names it in messages.
Status check_gltf_bytes(std::string_view bytes, bool binary, const std::string& path, const std::string& base_dir);
// Reads `path` (regular files only; ".glb" binary, else JSON) and checks it.
Status check_gltf_file(const std::string& path);

}  // namespace body
