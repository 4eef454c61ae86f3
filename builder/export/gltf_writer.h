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
// With `meshopt` (binary only): KHR_mesh_quantization (positions as unsigned
// 16-bit codes over the model's bounds, the dequantization folded into the
// node's matrix: a .bpm model's codes come out unchanged; normals as normalized
// 16-bit) and EXT_meshopt_compression (meshoptimizer's vertex codec 0 and index
// codec 1 on every buffer view; the uncompressed buffer is a fallback without
// data), both required extensions.
// Written atomically. Output passes the Khronos glTF-Validator with no errors
// and no data warnings (tests/export).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "builder/export/export_scene.h"
#include "shared/error.h"

namespace body::exporter {

// Defined beside tinygltf's implementation (this writer's object). Any other
// user of tinygltf calls it so that this object is linked: libdraco.so (in
// assimp's link interface) exports a tinygltf of its own, of another version,
// which would otherwise satisfy tinygltf's symbols first.
void link_tinygltf();

struct GltfOptions {
    bool binary = true;
    bool meshopt = false;  // quantized + meshopt-compressed (.glb only)
};

Status write_gltf(const std::string& path, const ExportScene& scene, const GltfOptions& options);

// A GLB whose buffer views all live in buffer 0 (as write_gltf makes them) ->
// the same GLB with EXT_meshopt_compression on every view (gltf_meshopt.cpp).
Result<std::vector<uint8_t>> meshopt_compress_glb(std::span<const uint8_t> glb);

}  // namespace body::exporter
