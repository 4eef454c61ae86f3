// The .bpm writer: progressive meshes -> sections (shared/pm/FORMAT.md).
//
// Phases: quantize (16-bit positions in a float bounding box, 8-bit octahedral
// normals), encode the base chunk, encode split chunks (meshoptimizer vertex and
// index codecs; index patches as bit masks over the parent's corners, computed
// by replaying the decoder's SplitReplay), frame sections with CRCs.
#include <meshoptimizer.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "builder/lod/simplify.h"
#include "shared/atomic_file.h"
#include "shared/pm/bpm_format.h"

namespace body::lod {
namespace {

using pm::put_f32;
using pm::put_u16;
using pm::put_u32;

struct Quantized {
    float lo[3], hi[3];
    std::vector<uint16_t> q;   // 3 per vertex
    std::vector<uint8_t> oct;  // 2 per vertex
};

float round_down(double x) {
    float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}
float round_up(double x) {
    float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

Quantized quantize(const ProgressiveBuild& pm, bool normals) {
    Quantized z;
    Aabb box = mesh_bounds(pm.positions);
    for (int k = 0; k < 3; ++k) {
        z.lo[k] = round_down(box.min[k]);
        z.hi[k] = round_up(box.max[k]);
    }
    const size_t n = pm.positions.size();
    z.q.resize(n * 3);
    z.oct.assign(n * 2, 0);
    for (size_t v = 0; v < n; ++v) {
        for (int k = 0; k < 3; ++k) z.q[v * 3 + k] = pm::quantize16(pm.positions[v][k], z.lo[k], z.hi[k]);
        if (normals) pm::oct_encode8(pm.normals[v].x, pm.normals[v].y, pm.normals[v].z, &z.oct[v * 2]);
    }
    return z;
}

void put_section(std::vector<uint8_t>& out, uint32_t tag, uint32_t structure, const std::vector<uint8_t>& payload) {
    const size_t start = out.size();
    put_u32(out, tag);
    put_u16(out, uint16_t(structure));
    put_u16(out, 0);
    put_u32(out, uint32_t(payload.size()));
    out.insert(out.end(), payload.begin(), payload.end());
    put_u32(out, pm::crc32({out.data() + start, out.size() - start}));
}

template <typename T>
void put_vertex_codec(std::vector<uint8_t>& out, const std::vector<T>& items) {
    std::vector<uint8_t> buf(meshopt_encodeVertexBufferBound(items.size(), sizeof(T)));
    buf.resize(meshopt_encodeVertexBuffer(buf.data(), buf.size(), items.data(), items.size(), sizeof(T)));
    put_u32(out, uint32_t(buf.size()));
    out.insert(out.end(), buf.begin(), buf.end());
}

// Encodes triangles and returns them as the decoder will see them (the codec may
// rotate a triangle's corners, keeping its winding).
std::vector<uint32_t> put_index_codec(std::vector<uint8_t>& out, const std::vector<uint32_t>& indices,
                                      size_t vertex_count) {
    std::vector<uint8_t> buf(meshopt_encodeIndexBufferBound(indices.size(), vertex_count));
    buf.resize(meshopt_encodeIndexBuffer(buf.data(), buf.size(), indices.data(), indices.size()));
    put_u32(out, uint32_t(buf.size()));
    out.insert(out.end(), buf.begin(), buf.end());
    std::vector<uint32_t> decoded(indices.size());
    [[maybe_unused]] int rc = meshopt_decodeIndexBuffer(decoded.data(), decoded.size(), 4, buf.data(), buf.size());
    assert(rc == 0);
    return decoded;
}

struct StructureSections {
    std::vector<uint8_t> info, base;
    std::vector<std::vector<uint8_t>> chunks;
};

Result<StructureSections> encode_structure(const Mesh& mesh, const ProgressiveBuild& pm, const LodOptions& options) {
    StructureSections out;
    const Quantized z = quantize(pm, options.normals);
    const size_t nv = pm.positions.size(), nf = pm.indices.size() / 3, ns = pm.splits.size();
    const size_t chunk = std::max<size_t>(options.chunk_splits, 1);

    // INFO
    std::string name = mesh.name.substr(0, 65535);
    put_u16(out.info, uint16_t(name.size()));
    out.info.insert(out.info.end(), name.begin(), name.end());
    for (int k = 0; k < 3; ++k) put_f32(out.info, float(mesh.color[k]));
    for (int k = 0; k < 3; ++k) put_f32(out.info, z.lo[k]);
    for (int k = 0; k < 3; ++k) put_f32(out.info, z.hi[k]);
    put_u32(out.info, options.normals ? 1u : 0u);
    for (size_t v : {pm.base_vertices, pm.base_faces, ns, nf, chunk}) put_u32(out.info, uint32_t(v));

    // BASE
    std::vector<pm::BaseVertex> base(pm.base_vertices);
    for (size_t v = 0; v < pm.base_vertices; ++v) {
        base[v] = {{z.q[v * 3], z.q[v * 3 + 1], z.q[v * 3 + 2]}, {z.oct[v * 2], z.oct[v * 2 + 1]}};
    }
    put_vertex_codec(out.base, base);
    std::vector<uint32_t> base_idx(pm.indices.begin(), pm.indices.begin() + ptrdiff_t(pm.base_faces * 3));
    pm::SplitReplay replay;
    replay.reset(nv, nf);
    replay.add_faces(0, put_index_codec(out.base, base_idx, pm.base_vertices));

    // SPLT chunks
    std::vector<uint32_t> scratch, moved;
    size_t face = pm.base_faces;
    for (size_t first = 0; first < ns; first += chunk) {
        const size_t count = std::min(chunk, ns - first);
        size_t chunk_faces = 0;
        for (size_t j = first; j < first + count; ++j) chunk_faces += pm.splits[j].face_count;
        std::vector<uint32_t> idx(pm.indices.begin() + ptrdiff_t(face * 3),
                                  pm.indices.begin() + ptrdiff_t((face + chunk_faces) * 3));
        std::vector<uint8_t> payload, vpart, ipart, topo;
        const std::vector<uint32_t> decoded = put_index_codec(ipart, idx, nv);
        std::vector<pm::SplitVertex> recs(count);
        size_t cursor = 0;
        for (size_t j = first; j < first + count; ++j) {
            const VertexSplit& sp = pm.splits[j];
            const uint32_t child = uint32_t(pm.base_vertices + j), parent = sp.parent;
            // Bit i: the i-th corner of the parent (ascending) belongs to a patched face.
            replay.corners_of(parent, scratch);
            uint64_t mask = 0;
            for (size_t i = 0; i < scratch.size(); ++i) {
                const uint32_t f = scratch[i] / 3;
                auto b = pm.patch_faces.begin() + pm.patch_begin[j], e = pm.patch_faces.begin() + pm.patch_begin[j + 1];
                if (std::find(b, e, f) != e) {
                    if (i >= 64)
                        return runtime_error("lod: '" + mesh.name + "': parent fan too large at split " +
                                             std::to_string(j));
                    mask |= uint64_t(1) << i;
                }
            }
            replay.apply_mask(parent, child, mask, scratch, moved);
            if (moved.size() != pm.patch_begin[j + 1] - pm.patch_begin[j])
                return runtime_error("lod: '" + mesh.name + "': index patches of split " + std::to_string(j) +
                                     " do not replay");
            replay.add_faces(face, {decoded.data() + cursor * 3, sp.face_count * 3});
            face += sp.face_count;
            cursor += sp.face_count;
            pm::put_varint(topo, sp.face_count);
            pm::put_varint(topo, mask);
            pm::SplitVertex& r = recs[j - first];
            for (int k = 0; k < 3; ++k) r.dq[k] = pm::zigzag16(z.q[size_t(child) * 3 + k], z.q[size_t(parent) * 3 + k]);
            for (int k = 0; k < 2; ++k)
                r.doct[k] = pm::zigzag8(z.oct[size_t(child) * 2 + k], z.oct[size_t(parent) * 2 + k]);
            r.parent_delta = child - parent;
            r.error = round_up(sp.error);
        }
        put_vertex_codec(vpart, recs);
        put_u32(payload, uint32_t(first));
        put_u32(payload, uint32_t(count));
        put_u32(payload, uint32_t(chunk_faces));
        payload.insert(payload.end(), vpart.begin(), vpart.end());
        payload.insert(payload.end(), ipart.begin(), ipart.end());
        put_u32(payload, uint32_t(topo.size()));
        payload.insert(payload.end(), topo.begin(), topo.end());
        out.chunks.push_back(std::move(payload));
    }
    return out;
}

}  // namespace

Result<std::vector<uint8_t>> encode_bpm(std::span<const Mesh> meshes, const LodOptions& options) {
    if (meshes.empty()) return input_error("lod: no meshes to write");
    if (meshes.size() > 65535) return input_error("lod: too many structures (" + std::to_string(meshes.size()) + ")");
    std::vector<StructureSections> parts;
    for (const Mesh& m : meshes) {
        auto pm = build_progressive_mesh(m, options);
        if (!pm) return pm.error();
        auto sec = encode_structure(m, *pm, options);
        if (!sec) return sec.error();
        parts.push_back(std::move(*sec));
    }
    std::vector<uint8_t> out(pm::kMagic, pm::kMagic + 4);
    put_u16(out, pm::kVersion);
    put_u16(out, 0);
    put_u32(out, uint32_t(meshes.size()));
    put_u32(out, pm::crc32({out.data(), 12}));
    // All structures become drawable first, then their refinements arrive interleaved.
    for (size_t s = 0; s < parts.size(); ++s) {
        put_section(out, pm::kTagInfo, uint32_t(s), parts[s].info);
        put_section(out, pm::kTagBase, uint32_t(s), parts[s].base);
    }
    for (size_t c = 0;; ++c) {
        bool any = false;
        for (size_t s = 0; s < parts.size(); ++s) {
            if (c >= parts[s].chunks.size()) continue;
            put_section(out, pm::kTagSplits, uint32_t(s), parts[s].chunks[c]);
            any = true;
        }
        if (!any) break;
    }
    std::vector<uint8_t> end;
    put_u32(end, uint32_t(meshes.size()));
    put_section(out, pm::kTagEnd, 0, end);
    return out;
}

Status write_bpm_from_meshes(const std::string& path, std::span<const Mesh> meshes, const LodOptions& options) {
    auto bytes = encode_bpm(meshes, options);
    if (!bytes) return bytes.error();
    return write_file_atomically(path, *bytes);
}

}  // namespace body::lod
