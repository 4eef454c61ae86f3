#pragma once
// Wavefront OBJ: writing (one `o NAME` per mesh, optional normals, written
// atomically) and reading (through tinyobjloader; one Mesh per object/group).
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/mesh.h"

namespace body {

struct ObjWriteOptions {
    bool normals = false;  // write `vn` per vertex (computed when a mesh has none)
    int precision = 9;     // significant digits for coordinates
    unsigned threads = 1;  // rows spelled on this many threads (the same file)
};

Status write_obj(const std::string& path, std::span<const Mesh> meshes, const ObjWriteOptions& options = {});

// Reads all objects; polygons are fan-triangulated, vertices welded by index.
// An object without a name takes the file's stem ("bunny" for bunny.obj).
Result<std::vector<Mesh>> read_obj(const std::string& path);
// The same from OBJ text already in memory; `path` names it in messages
// ("PATH: line N: reason") and names unnamed objects.
Result<std::vector<Mesh>> parse_obj(const std::string& text, const std::string& path);

// Reads all objects and merges them into one mesh (welding identical positions).
Result<Mesh> read_obj_merged(const std::string& path);

}  // namespace body
