#pragma once
// Meshes in, whatever the format: OBJ through tinyobjloader (shared/obj_io.h);
// VRML97 .wrl through our reader (vrml_reader.h: assimp 5.2 reads only VRML 1.0);
// STL, PLY, glTF 2.0 (.gltf/.glb) through Open Asset Import (Debian
// libassimp-dev) when this bodygen was built with it.
//
// One Mesh per mesh instance: triangulated, identical vertices joined (STL
// repeats them per facet), node transforms applied. Names: the node's name,
// else the mesh's, else the file's stem (numbered when several). Units:
// glTF's metres become millimetres (x 1000, the scene's unit); STL and PLY are
// taken as millimetres. Colours: VRML's diffuseColor goes to mesh.color; the
// other formats leave the default grey, which exhibits treat as unset.
// Errors (exit 2): one line "PATH: reason" (unreadable, not a mesh, no triangles).
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/mesh.h"

namespace body {

// True for the extensions read_mesh_file() reads in this build.
bool is_mesh_file(const std::string& path);
Result<std::vector<Mesh>> read_mesh_file(const std::string& path);

}  // namespace body
