#pragma once
// The bytes of a full mesh through two static-mesh codecs, printed beside a
// .bpm's bytes per vertex split (bodygen info, bench_pm): what a progressive
// order costs against sending the finished mesh. Both at the .bpm's
// quantization: 16-bit position codes, 8-bit octahedral normals.
#include <cstddef>
#include <cstdint>

namespace body::lod {

// meshoptimizer: vertex cache then vertex fetch order, then
// meshopt_encodeVertexBuffer over 8-byte vertices (3 codes + 2 normal bytes,
// the .bpm's BASE layout) plus meshopt_encodeIndexBuffer. `oct`: 2 bytes per
// vertex, or nullptr (normals sent as zeros, which the codec nearly drops).
size_t meshopt_codec_bytes(const uint16_t* qpos, const uint8_t* oct, size_t vertex_count, const uint32_t* indices,
                           size_t index_count);

// Draco (Debian libdraco-dev), compression level 10 as `draco_encoder -cl 10`
// (edgebreaker, speed 0): positions quantized to 16 bits over the codes' range
// (one code a step), normals (when `oct` is given) to 8 bits. 0 when bodygen is
// built without Draco (draco_available() is false).
size_t draco_codec_bytes(const uint16_t* qpos, const uint8_t* oct, size_t vertex_count, const uint32_t* indices,
                         size_t index_count);
bool draco_available();

}  // namespace body::lod
