// The .bpm writer: progressive meshes -> sections (shared/pm/FORMAT.md).
//
// Phases: quantize (16-bit positions in a float bounding box, 8-bit octahedral
// normals), encode the base chunk (meshoptimizer vertex and index codecs), encode
// split chunks (every split replayed on the decoder's SplitReplay: its topology as
// two positions in the parent's ordered fan, or neighbour numbers and a patch mask
// when it is not a manifold fan split; positions as residuals of the predictions
// the reader makes too -- ring centroids, and along the parent's normal the plane
// through it; the child's normal as a residual of its faces' normal after the
// split; all values through pm::SplitEncoder), frame sections with CRCs.
#include <meshoptimizer.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "builder/lod/simplify.h"
#include "shared/atomic_file.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/large_array.h"
#include "shared/pm/prediction.h"
#include "shared/pm/quantize.h"
#include "shared/pm/split_codec.h"
#include "shared/pm/split_replay.h"

namespace body::lod {
namespace {

using pm::put_f32;
using pm::put_u16;
using pm::put_u32;
using pm::quantize16;

using pm::prefetch;

struct Quantized {
    float lo[3], hi[3];
    std::vector<uint16_t> q;   // 3 per vertex
    std::vector<uint8_t> oct;  // 2 per vertex
};

// Rounds a non-negative error up to 8 significant bits (the low 16 bits of the
// binary32 become zero: the file codes the high 16 bits' steps down); still an
// upper bound, still monotonic.
float round_up_coarse(double x) {
    const float f = pm::float_at_or_above(x);
    uint32_t u;
    std::memcpy(&u, &f, 4);
    if (u & 0xffffu) u = (u | 0xffffu) + 1;
    float r;
    std::memcpy(&r, &u, 4);
    return r;
}

Quantized quantize(const ProgressiveBuild& pm, bool normals) {
    Quantized z;
    // Every position a vertex takes at some level: where it appears, and where the
    // splits move parents.
    Aabb box = mesh_bounds(pm.positions);
    for (const VertexSplit& sp : pm.splits) {
        box.extend(sp.parent_from);
        box.extend(sp.parent_to);
    }
    for (int k = 0; k < 3; ++k) {
        z.lo[k] = pm::float_at_or_below(box.min[k]);
        z.hi[k] = pm::float_at_or_above(box.max[k]);
    }
    const size_t n = pm.positions.size();
    z.q.resize(n * 3);
    z.oct.assign(n * 2, 0);
    for (size_t v = 0; v < n; ++v) {
        for (int k = 0; k < 3; ++k) z.q[v * 3 + k] = quantize16(pm.positions[v][k], z.lo[k], z.hi[k]);
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

// Bit i: the i-th corner (ascending) of the split's parent belongs to a face the
// split patches.
// (file_face: the builder's face numbers as the file has them.)
// (corners: the parent's, as SplitReplay::corners_of lists them.)
uint64_t mask_of(const ProgressiveBuild& pm, const std::vector<uint32_t>& file_face, size_t j,
                 const std::vector<uint32_t>& corners) {
    uint64_t mask = 0;
    for (uint32_t i = pm.patch_begin[j]; i < pm.patch_begin[j + 1]; ++i) {
        const uint32_t f = file_face[pm.patch_faces[i]];
        for (size_t n = 0; n < corners.size() && n < 64; ++n)
            if (corners[n] / 3 == f) mask |= uint64_t(1) << n;
    }
    return mask;
}

Error split_error(const Mesh& mesh, size_t j, const char* what) {
    return runtime_error("lod: '" + mesh.name + "': split " + std::to_string(j) + " " + what);
}

constexpr uint32_t kInfinityBits = 0x7f800000u;  // +inf: the error before the first split
uint32_t error_bits(float e) {
    uint32_t u;
    std::memcpy(&u, &e, 4);
    return u;
}

// A split in the compact form: the parent is an interior manifold vertex, the
// new faces are (c, p, ring[start]) and (c, ring[start + length], p) and the
// fan faces start .. start + length - 1 move to the child. length 0: not such a split.
struct FanSplit {
    uint32_t start = 0, length = 0, fan = 0;
    bool swapped = false;  // the builder made (c, vr, p) first: the file has them the other way round
};

FanSplit fan_split(const pm::SplitReplay& replay, uint32_t parent, const std::vector<uint32_t>& corners,
                   const std::vector<uint32_t>& faces, uint64_t mask, uint32_t* ring, uint8_t* at) {
    FanSplit none;
    const size_t k = replay.ordered_fan(corners.data(), corners.size(), ring, at);
    if (k == 0) return none;
    none.fan = uint32_t(k);
    if (faces.size() != 6) return none;
    const bool swapped = faces[1] != parent;
    const uint32_t* left = swapped ? &faces[3] : &faces[0];   // (c, p, vl)
    const uint32_t* right = swapped ? &faces[0] : &faces[3];  // (c, vr, p)
    if (left[1] != parent || right[2] != parent) return none;
    size_t a = k, b = k;
    for (size_t t = 0; t < k; ++t) {
        if (ring[t] == left[2]) a = t;
        if (ring[t] == right[1]) b = t;
    }
    if (a == k || b == k || a == b) return none;
    const size_t length = (b + k - a) % k;
    uint64_t expected = 0;
    for (size_t t = 0; t < length; ++t) expected |= uint64_t(1) << at[(a + t) % k];
    if (expected != mask) return none;
    FanSplit s;
    s.start = uint32_t(a);
    s.length = uint32_t(length);
    s.fan = uint32_t(k);
    s.swapped = swapped;
    return s;
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

    // SPLT chunks, on one thread. Measured 2026-11-26 and dropped: the topology (replay,
    // masks, fans) of chunk c + 1 on a second thread while the values of chunk c were
    // coded here (same bytes). On the benchmark VM each pass ran 1.5-2.2x slower beside
    // the other (both are bound by memory latency, and the two vCPUs share the cache):
    // bunny encode 23-25 ms either way, 1.1M-triangle bunny 0.50-0.63 -> 0.41-0.50 s,
    // about 3% of its build, for a second copy of the chunk's topology and a thread per chunk.
    std::vector<uint32_t> moved;
    constexpr size_t kAhead0 = 32, kAhead1 = 20, kAhead2 = 12, kAhead3 = 6;
    // The file puts the two new faces of a fan split in one order (one symbol less
    // per split): the builder's face numbers as the file has them.
    std::vector<uint32_t> file_face(nf);
    for (size_t f = 0; f < nf; ++f) file_face[f] = uint32_t(f);
    size_t face = pm.base_faces;
    // Quantized positions at the level being encoded (the reader tracks the same).
    std::vector<uint16_t> cur = z.q;
    int32_t axis_weight[3], plane_weight[3];
    pm::normal_axis_weights(z.lo, z.hi, axis_weight);
    pm::plane_axis_weights(z.lo, z.hi, plane_weight);
    uint32_t previous_error = kInfinityBits;
    pm::SplitEncoder values;  // one per chunk, its storage reused
    for (size_t first = 0; first < ns; first += chunk) {
        const size_t count = std::min(chunk, ns - first);
        size_t chunk_faces = 0;
        for (size_t j = first; j < first + count; ++j) chunk_faces += pm.splits[j].face_count;
        std::vector<uint8_t> payload, topo;
        values.clear();
        // All parents of the chunk first: the reader prefetches their data splits ahead.
        for (size_t j = first; j < first + count; ++j)
            values.put(pm::kCtxParentDelta, uint32_t(pm.base_vertices + j) - pm.splits[j].parent - 1);
        std::vector<uint32_t> parent_corners, faces;
        uint32_t ring[64];
        uint8_t fan_at[64];
        for (size_t j = first; j < first + count; ++j) {
            const VertexSplit& sp = pm.splits[j];
            const uint32_t child = uint32_t(pm.base_vertices + j), parent = sp.parent;
            // The replay is bound by memory latency (a parent is anywhere in the mesh): the
            // data of the splits a few steps ahead is requested in stages, as the reader does.
            if (j + kAhead0 < ns) replay.prefetch(pm.splits[j + kAhead0].parent, 0);
            if (j + kAhead1 < ns) {
                const uint32_t p = pm.splits[j + kAhead1].parent;
                replay.prefetch(p, 1);
                prefetch(&cur[size_t(p) * 3]);
                prefetch(&z.oct[size_t(p) * 2]);
                for (uint32_t i = pm.patch_begin[j + kAhead1]; i < pm.patch_begin[j + kAhead1 + 1]; ++i)
                    prefetch(&file_face[pm.patch_faces[i]]);
            }
            if (j + kAhead2 < ns) replay.prefetch(pm.splits[j + kAhead2].parent, 2);
            if (j + kAhead3 < ns) replay.prefetch(pm.splits[j + kAhead3].parent, 3, cur.data());
            replay.corners_of(parent, parent_corners);
            const uint64_t mask = mask_of(pm, file_face, j, parent_corners);
            // New faces are (child, parent, a) or (child, a, parent), a a neighbour of the
            // parent before the split.
            faces.clear();
            for (uint32_t f = 0; f < sp.face_count; ++f) {
                const uint32_t* t = &pm.indices[(face + f) * 3];
                int k = 0;
                while (k < 3 && t[k] != child) ++k;
                if (k == 3) return split_error(mesh, j, "adds a face without its child");
                const uint32_t b = t[(k + 1) % 3], a = t[(k + 2) % 3];
                if (b == parent)
                    faces.insert(faces.end(), {child, parent, a});
                else if (a == parent)
                    faces.insert(faces.end(), {child, b, parent});
                else
                    return split_error(mesh, j, "adds a face without its parent");
            }
            const FanSplit fan = fan_split(replay, parent, parent_corners, faces, mask, ring, fan_at);
            if (fan.swapped) {
                std::rotate(faces.begin(), faces.begin() + 3, faces.end());
                std::swap(file_face[face], file_face[face + 1]);
            }
            // Positions: the parent's before (cur) and after the split, the child's.
            uint16_t from[3], to[3], at[3];
            for (int k = 0; k < 3; ++k) {
                from[k] = cur[size_t(parent) * 3 + k];
                if (from[k] != quantize16(sp.parent_from[k], z.lo[k], z.hi[k]))
                    return split_error(mesh, j, "moves its parent from elsewhere than it is");
                to[k] = quantize16(sp.parent_to[k], z.lo[k], z.hi[k]);
                at[k] = z.q[size_t(child) * 3 + k];
            }
            const bool moves = from[0] != to[0] || from[1] != to[1] || from[2] != to[2];
            const uint32_t form = fan.length == 0 ? pm::kTopoGeneral : pm::kTopoFan;
            values.put(pm::kCtxKind, form * 2 + (moves ? 1 : 0));
            const uint32_t error = error_bits(round_up_coarse(sp.error));
            if (error > previous_error) return split_error(mesh, j, "has a larger error than the split before it");
            values.put(pm::kCtxErrorStep, (previous_error - error) >> 16);
            previous_error = error;
            pm::FanPrediction pred{{from[0], from[1], from[2]}, {0, 0, 0}, {0, 0, 0}};
            if (form == pm::kTopoGeneral) {
                // Neighbour numbers over the parent's corners and the patch mask.
                pm::put_varint(topo, (mask << 2) | sp.face_count);
                for (size_t f = 0; f < faces.size(); f += 3) {
                    const bool flipped = faces[f + 2] == parent;  // (child, a, parent)
                    const uint32_t third = flipped ? faces[f + 1] : faces[f + 2];
                    size_t n = 0;
                    while (n < 2 * parent_corners.size() && replay.neighbour(parent_corners.data(), n) != third) ++n;
                    if (n == 2 * parent_corners.size())
                        return split_error(mesh, j, "adds a face outside the parent's ring");
                    pm::put_varint(topo, uint64_t(n) * 2 + (flipped ? 1 : 0));
                }
            } else {
                values.put(pm::kCtxFanStart, fan.start);
                values.put(pm::kCtxFanLength, fan.length - 1);
                // The plane through the parent: its normal (when the file has normals).
                int64_t plane[3];
                pm::plane_normal(&z.oct[size_t(parent) * 2], plane_weight, plane);
                pm::predict_fan(cur.data(), ring, fan.fan, fan.start, fan.length, from,
                                options.normals ? plane : nullptr, pred);
            }
            // Positions: with a plane, the two other axes first, then the plane's axis.
            uint32_t order[3] = {0, 1, 2};
            if (pred.axis < 3) {
                pm::plane_axes(pred.axis, order[0], order[1]);
                order[2] = pred.axis;
            }
            for (uint32_t i = 0; i < 3; ++i) {
                const uint32_t k = order[i];
                if (i == 2 && pred.axis < 3) {
                    const uint16_t predicted = pm::plane_coordinate(pred, from, at, pred.child_dot, 4);
                    values.put_scaled(pm::kCtxChild0 + i, pm::zigzag16(at[k], predicted), pred.axis_shift);
                } else {
                    values.put_scaled(pm::kCtxChild0 + i, pm::zigzag16(at[k], pred.child[k]), pred.shift[k]);
                }
            }
            if (moves) {
                const int64_t offset = pred.axis < 3 ? pred.parent_dot - 4 * pm::plane_dot(pred, from, at) : 0;
                for (uint32_t i = 0; i < 3; ++i) {
                    const uint32_t k = order[i];
                    if (i == 2 && pred.axis < 3) {
                        const uint16_t predicted = pm::plane_coordinate(pred, from, to, offset, 8);
                        values.put_scaled(pm::kCtxParent0 + i, pm::zigzag16(to[k], predicted), pred.axis_shift);
                        continue;
                    }
                    const uint16_t reflected = pm::reflect16(from[k], at[k]);
                    const uint16_t predicted =
                        fan.length != 0 ? pm::midpoint16(reflected, pred.parent_centroid[k]) : reflected;
                    values.put_scaled(pm::kCtxParent0 + i, pm::zigzag16(to[k], predicted), pred.shift[k]);
                }
            }
            if (options.normals) {
                // The child's normal: from its faces after the split (fan form), else the parent's.
                uint8_t predicted[2] = {z.oct[size_t(parent) * 2], z.oct[size_t(parent) * 2 + 1]};
                if (form == pm::kTopoFan) pm::predict_normal(pred, from, to, axis_weight, predicted);
                for (int k = 0; k < 2; ++k)
                    values.put(pm::kCtxNormal0 + uint32_t(k), pm::zigzag8(z.oct[size_t(child) * 2 + k], predicted[k]));
            }
            // (parent_corners are still the parent's: nothing changed the replay since.)
            moved.resize(parent_corners.size());
            if (!replay.apply_mask(parent, child, mask, parent_corners.data(), parent_corners.size(), moved.data()) ||
                size_t(std::popcount(mask)) != pm.patch_begin[j + 1] - pm.patch_begin[j])
                return split_error(mesh, j, "index patches do not replay");
            replay.add_faces(face, faces);
            face += sp.face_count;
            for (int k = 0; k < 3; ++k) {
                cur[size_t(parent) * 3 + k] = to[k];
                cur[size_t(child) * 3 + k] = at[k];
            }
        }
        put_u32(payload, uint32_t(first));
        put_u32(payload, uint32_t(count));
        put_u32(payload, uint32_t(chunk_faces));
        std::vector<uint8_t> coded;
        values.finish(coded);
        put_u32(payload, uint32_t(coded.size()));
        payload.insert(payload.end(), coded.begin(), coded.end());
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
