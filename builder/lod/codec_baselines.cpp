// Static-mesh codec baselines (contract in codec_baselines.h).
#include "builder/lod/codec_baselines.h"

#include <meshoptimizer.h>

#include <vector>

#include "shared/pm/bpm_container.h"
#include "shared/pm/quantize.h"

#if BODY_WITH_DRACO
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#endif

namespace body::lod {

size_t meshopt_codec_bytes(const uint16_t* qpos, const uint8_t* oct, size_t vertex_count, const uint32_t* indices,
                           size_t index_count) {
    std::vector<pm::BaseVertex> vertices(vertex_count);
    for (size_t v = 0; v < vertex_count; ++v)
        vertices[v] = {{qpos[v * 3], qpos[v * 3 + 1], qpos[v * 3 + 2]},
                       {oct ? oct[v * 2] : uint8_t(0), oct ? oct[v * 2 + 1] : uint8_t(0)}};
    std::vector<uint32_t> ordered(index_count);
    meshopt_optimizeVertexCache(ordered.data(), indices, index_count, vertex_count);
    const size_t used = meshopt_optimizeVertexFetch(vertices.data(), ordered.data(), index_count, vertices.data(),
                                                    vertex_count, sizeof(pm::BaseVertex));
    std::vector<uint8_t> out(meshopt_encodeVertexBufferBound(used, sizeof(pm::BaseVertex)));
    const size_t vbytes =
        meshopt_encodeVertexBuffer(out.data(), out.size(), vertices.data(), used, sizeof(pm::BaseVertex));
    out.resize(meshopt_encodeIndexBufferBound(index_count, used));
    return vbytes + meshopt_encodeIndexBuffer(out.data(), out.size(), ordered.data(), index_count);
}

#if BODY_WITH_DRACO
bool draco_available() { return true; }

size_t draco_codec_bytes(const uint16_t* qpos, const uint8_t* oct, size_t vertex_count, const uint32_t* indices,
                         size_t index_count) {
    draco::Mesh mesh;
    mesh.set_num_points(uint32_t(vertex_count));
    const auto add = [&](draco::GeometryAttribute::Type type) {
        draco::GeometryAttribute a;
        a.Init(type, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
        return mesh.AddAttribute(a, true, uint32_t(vertex_count));
    };
    const int position = add(draco::GeometryAttribute::POSITION);
    const int normal = oct ? add(draco::GeometryAttribute::NORMAL) : -1;
    for (size_t v = 0; v < vertex_count; ++v) {
        const float p[3] = {float(qpos[v * 3]), float(qpos[v * 3 + 1]), float(qpos[v * 3 + 2])};
        mesh.attribute(position)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(v)), p);
        if (oct) {
            float n[3];
            pm::oct_decode8(&oct[v * 2], n);
            mesh.attribute(normal)->SetAttributeValue(draco::AttributeValueIndex(uint32_t(v)), n);
        }
    }
    for (size_t i = 0; i + 2 < index_count; i += 3)
        mesh.AddFace(
            {draco::PointIndex(indices[i]), draco::PointIndex(indices[i + 1]), draco::PointIndex(indices[i + 2])});
    draco::Encoder encoder;
    encoder.SetSpeedOptions(0, 0);  // draco_encoder -cl 10
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 16);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 8);
    draco::EncoderBuffer buffer;
    if (!encoder.EncodeMeshToBuffer(mesh, &buffer).ok()) return 0;
    return buffer.size();
}
#else
bool draco_available() { return false; }

size_t draco_codec_bytes(const uint16_t*, const uint8_t*, size_t, const uint32_t*, size_t) { return 0; }
#endif

}  // namespace body::lod
