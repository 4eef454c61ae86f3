#pragma once
// glTF 2.0 out, through tinygltf (Debian libtinygltf-dev): binary (.glb) or text
// (.gltf, the buffer embedded as a data URI).
//
// Layout: one root node named after the file, scaling millimetres to glTF's
// metres (0.001); under it one node per group (its name) holding its models'
// nodes, and the ungrouped models' nodes. A model node carries the model's name,
// its placement as `matrix` (omitted when identity) and a mesh of one indexed
// triangle primitive: POSITION (float, with min/max), NORMAL (unit floats, when
// the model has normals), indices (unsigned short or int) and a material named
// after the model with baseColorFactor = its colour, metallic 0, roughness 0.7.
// Written atomically. Output passes the Khronos glTF-Validator with no errors
// and no data warnings (tests/export).
#include <string>

#include "builder/export/export_scene.h"
#include "shared/error.h"

namespace body::exporter {

struct GltfOptions {
    bool binary = true;
};

Status write_gltf(const std::string& path, const ExportScene& scene, const GltfOptions& options);

}  // namespace body::exporter
