// STL, PLY, glTF via assimp; OBJ via tinyobjloader (contract in mesh_import.h).
#include "builder/mesh_import/mesh_import.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "builder/mesh_import/glb_check.h"
#include "builder/mesh_import/gltf_check.h"
#include "builder/mesh_import/ply_check.h"
#include "builder/mesh_import/stl_check.h"
#include "builder/mesh_import/vrml_reader.h"
#include "shared/obj_io.h"

#ifdef BODY_WITH_ASSIMP
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#endif

namespace body {
namespace {

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

#ifdef BODY_WITH_ASSIMP
void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, double unit, std::vector<Mesh>& out) {
    const aiMatrix4x4 world = parent * node.mTransformation;
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
        const aiMesh& am = *scene.mMeshes[node.mMeshes[k]];
        Mesh m;
        m.name = node.mName.length ? node.mName.C_Str() : am.mName.C_Str();
        aiMatrix3x3 rot(world);
        for (unsigned v = 0; v < am.mNumVertices; ++v) {
            const aiVector3D p = world * am.mVertices[v];
            m.positions.emplace_back(p.x * unit, p.y * unit, p.z * unit);
        }
        for (unsigned f = 0; f < am.mNumFaces; ++f) {
            const aiFace& face = am.mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines are not surfaces
            m.indices.insert(m.indices.end(), {face.mIndices[0], face.mIndices[1], face.mIndices[2]});
        }
        if (am.HasNormals()) {
            for (unsigned v = 0; v < am.mNumVertices; ++v) {
                aiVector3D n = rot * am.mNormals[v];
                n.Normalize();
                m.normals.emplace_back(n.x, n.y, n.z);
            }
        }
        if (m.triangle_count() > 0) out.push_back(std::move(m));
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) collect(scene, *node.mChildren[c], world, unit, out);
}

Result<std::vector<Mesh>> read_with_assimp(const std::string& path, const std::string& ext) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return input_error(path + ": no such file");
    // assimp trusts counts and reads past mismatches in these two: ours first.
    if (ext == ".ply")
        if (Status checked = check_ply_file(path); !checked) return checked.error();
    if (ext == ".stl")
        if (Status checked = check_stl_file(path); !checked) return checked.error();
    if (ext == ".glb")
        if (Status checked = check_glb_file(path); !checked) return checked.error();
    if (ext == ".gltf" || ext == ".glb")  // assimp drops faces whose indices are past the vertices
        if (Status checked = check_gltf_file(path); !checked) return checked.error();
    Assimp::Importer importer;
    const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                                       aiProcess_FindInvalidData | aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        std::string why = importer.GetErrorString();
        std::replace(why.begin(), why.end(), '\n', ' ');
        return input_error(path + ": not a readable mesh file: " + (why.empty() ? "unknown reason" : why));
    }
    const double unit = (ext == ".gltf" || ext == ".glb") ? 1000.0 : 1.0;  // glTF metres -> mm
    std::vector<Mesh> meshes;
    collect(*scene, *scene->mRootNode, aiMatrix4x4(), unit, meshes);
    if (meshes.empty()) return input_error(path + ": no triangles");
    const std::string stem = std::filesystem::path(path).stem().string();
    for (size_t i = 0; i < meshes.size(); ++i)
        if (meshes[i].name.empty()) meshes[i].name = meshes.size() == 1 ? stem : stem + "_" + std::to_string(i + 1);
    return meshes;
}
#endif

}  // namespace

bool is_mesh_file(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".obj" || ext == ".wrl") return true;
#ifdef BODY_WITH_ASSIMP
    return ext == ".stl" || ext == ".ply" || ext == ".gltf" || ext == ".glb";
#else
    return false;
#endif
}

Result<std::vector<Mesh>> read_mesh_file(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".obj") return read_obj(path);
    if (ext == ".wrl") return read_vrml(path);
#ifdef BODY_WITH_ASSIMP
    if (ext == ".stl" || ext == ".ply" || ext == ".gltf" || ext == ".glb") return read_with_assimp(path, ext);
    return input_error(path + ": not a mesh file (expected .obj, .wrl, .stl, .ply, .gltf or .glb)");
#else
    return input_error(path + ": not a mesh file (this bodygen reads .obj and .wrl; STL/PLY/glTF need libassimp-dev)");
#endif
}

}  // namespace body
