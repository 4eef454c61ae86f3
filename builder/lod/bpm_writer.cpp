// The .bpm writer (bpm_writer.h): progressive meshes -> sections (shared/pm/FORMAT.md).
//
// Phases: quantize (16-bit positions in a float bounding box, 8-bit octahedral
// normals), encode the base chunk (meshoptimizer vertex and index codecs), encode
// split chunks (every split replayed on the decoder's SplitReplay: its topology as
// two positions in the parent's ordered fan, or neighbour numbers and a patch mask
// when it is not a manifold fan split; positions as residuals of the predictions
// the reader makes too -- ring centroids, and along the parent's normal the plane
// through it; the child's normal as a residual of its faces' normal after the
// split; all values through pm::SplitEncoder), frame sections with CRCs.
#include "builder/lod/bpm_writer.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

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

// INFO: name, colour, the quantization box, flags and counts.
std::vector<uint8_t> info_section(const Mesh& mesh, const ProgressiveBuild& pm, const Quantized& z, bool normals,
                                  size_t chunk) {
    std::vector<uint8_t> info;
    std::string name = mesh.name.substr(0, 65535);
    put_u16(info, uint16_t(name.size()));
    info.insert(info.end(), name.begin(), name.end());
    for (int k = 0; k < 3; ++k) put_f32(info, float(mesh.color[k]));
    for (int k = 0; k < 3; ++k) put_f32(info, z.lo[k]);
    for (int k = 0; k < 3; ++k) put_f32(info, z.hi[k]);
    put_u32(info, normals ? 1u : 0u);
    for (size_t v : {pm.base_vertices, pm.base_faces, pm.splits.size(), pm.indices.size() / 3, chunk})
        put_u32(info, uint32_t(v));
    return info;
}

// BASE: the base mesh through meshoptimizer's codecs; its faces go to the replay
// as the reader will decode them.
std::vector<uint8_t> base_section(const ProgressiveBuild& pm, const Quantized& z, pm::SplitReplay& replay) {
    std::vector<uint8_t> base_bytes;
    std::vector<pm::BaseVertex> base(pm.base_vertices);
    for (size_t v = 0; v < pm.base_vertices; ++v) {
        base[v] = {{z.q[v * 3], z.q[v * 3 + 1], z.q[v * 3 + 2]}, {z.oct[v * 2], z.oct[v * 2 + 1]}};
    }
    put_vertex_codec(base_bytes, base);
    std::vector<uint32_t> base_idx(pm.indices.begin(), pm.indices.begin() + ptrdiff_t(pm.base_faces * 3));
    replay.add_faces(0, put_index_codec(base_bytes, base_idx, pm.base_vertices));
    return base_bytes;
}

// What encoding the SPLT chunks carries from split to split: the replay and the
// codes at the level being encoded (the reader tracks the same), and the scratch
// of one split.
struct SplitWriter {
    SplitWriter(const Mesh& m, const ProgressiveBuild& p, const Quantized& q, bool with_normals)
        : mesh(m), pm(p), z(q), normals(with_normals), file_face(p.indices.size() / 3), cur(q.q), face(p.base_faces) {
        replay.reset(p.positions.size(), p.indices.size() / 3);
        for (size_t f = 0; f < file_face.size(); ++f) file_face[f] = uint32_t(f);
        pm::normal_axis_weights(z.lo, z.hi, axis_weight);
        pm::plane_axis_weights(z.lo, z.hi, plane_weight);
        exact.assign(p.positions.size(), 1);
    }
    const Mesh& mesh;
    const ProgressiveBuild& pm;
    const Quantized& z;
    const bool normals;
    pm::SplitReplay replay;
    // The file puts the two new faces of a fan split in one order (one symbol less
    // per split): the builder's face numbers as the file has them.
    std::vector<uint32_t> file_face;
    std::vector<uint16_t> cur;                     // 3 per vertex: codes at the level being encoded
    std::vector<uint8_t> exact;                    // per vertex: cur holds its builder position (not on a coarser grid)
    std::vector<uint8_t> child_grid, parent_grid;  // per split: the grids plan_grids allows
    int32_t axis_weight[3], plane_weight[3];
    uint32_t previous_error = kInfinityBits;
    size_t face;                // the next split's first new face
    pm::SplitEncoder values;    // one chunk's values, its storage reused
    std::vector<uint8_t> topo;  // one chunk's topology records
    std::vector<uint32_t> parent_corners, faces, moved;
    pm::SplitSizes* sizes = nullptr;  // where the SPLT bytes go, when asked
};

// Per split, the grids of the child's position and of the parent's after it: a
// position that a later split moves (in the builder's codes) is intermediate, and
// every level showing it has at least that split's error (FORMAT.md, version 6).
// Without `coarse` every grid is 0: every position exact.
void plan_grids(SplitWriter& w, bool coarse) {
    const ProgressiveBuild& pm = w.pm;
    const size_t ns = pm.splits.size();
    const double step = pm::largest_step(w.z.lo, w.z.hi);
    w.child_grid.assign(ns, 0);
    w.parent_grid.assign(ns, 0);
    if (!coarse || !(step > 0)) return;
    std::vector<float> next_move(pm.positions.size(), 0.0f);  // per vertex: error of the split moving it next
    for (size_t j = ns; j-- > 0;) {
        const VertexSplit& sp = pm.splits[j];
        w.child_grid[j] = uint8_t(pm::coarsest_grid(next_move[pm.base_vertices + j], step));
        w.parent_grid[j] = uint8_t(pm::coarsest_grid(next_move[sp.parent], step));
        bool moves = false;
        for (int k = 0; k < 3; ++k)
            moves |= quantize16(sp.parent_from[k], w.z.lo[k], w.z.hi[k]) !=
                     quantize16(sp.parent_to[k], w.z.lo[k], w.z.hi[k]);
        if (moves) next_move[sp.parent] = round_up_coarse(sp.error);
    }
}

// The replay is bound by memory latency (a parent is anywhere in the mesh): the
// data of the splits a few steps ahead is requested in stages, as the reader does.
void prefetch_ahead(const SplitWriter& w, size_t j) {
    constexpr size_t kAhead0 = 32, kAhead1 = 20, kAhead2 = 12, kAhead3 = 6;
    const ProgressiveBuild& pm = w.pm;
    const size_t ns = pm.splits.size();
    if (j + kAhead0 < ns) w.replay.prefetch(pm.splits[j + kAhead0].parent, 0);
    if (j + kAhead1 < ns) {
        const uint32_t p = pm.splits[j + kAhead1].parent;
        w.replay.prefetch(p, 1);
        prefetch(&w.cur[size_t(p) * 3]);
        prefetch(&w.z.oct[size_t(p) * 2]);
        for (uint32_t i = pm.patch_begin[j + kAhead1]; i < pm.patch_begin[j + kAhead1 + 1]; ++i)
            prefetch(&w.file_face[pm.patch_faces[i]]);
    }
    if (j + kAhead2 < ns) w.replay.prefetch(pm.splits[j + kAhead2].parent, 2);
    if (j + kAhead3 < ns) w.replay.prefetch(pm.splits[j + kAhead3].parent, 3, w.cur.data());
}

// Split j's new faces into w.faces as (child, parent, a) or (child, a, parent), a a
// neighbour of the parent before the split.
Status new_faces(SplitWriter& w, size_t j, uint32_t child, uint32_t parent) {
    w.faces.clear();
    for (uint32_t f = 0; f < w.pm.splits[j].face_count; ++f) {
        const uint32_t* t = &w.pm.indices[(w.face + f) * 3];
        int k = 0;
        while (k < 3 && t[k] != child) ++k;
        if (k == 3) return split_error(w.mesh, j, "adds a face without its child");
        const uint32_t b = t[(k + 1) % 3], a = t[(k + 2) % 3];
        if (b == parent)
            w.faces.insert(w.faces.end(), {child, parent, a});
        else if (a == parent)
            w.faces.insert(w.faces.end(), {child, b, parent});
        else
            return split_error(w.mesh, j, "adds a face without its parent");
    }
    return ok_status();
}

// The general form's topology record: the patch mask, then per new face its third
// vertex as a neighbour number over the parent's corners.
Status put_general_topology(SplitWriter& w, size_t j, uint64_t mask, uint32_t parent) {
    pm::put_varint(w.topo, (mask << 2) | w.pm.splits[j].face_count);
    const std::vector<uint32_t>& corners = w.parent_corners;
    for (size_t f = 0; f < w.faces.size(); f += 3) {
        const bool flipped = w.faces[f + 2] == parent;  // (child, a, parent)
        const uint32_t third = flipped ? w.faces[f + 1] : w.faces[f + 2];
        size_t n = 0;
        while (n < 2 * corners.size() && w.replay.neighbour(corners.data(), n) != third) ++n;
        if (n == 2 * corners.size()) return split_error(w.mesh, j, "adds a face outside the parent's ring");
        pm::put_varint(w.topo, uint64_t(n) * 2 + (flipped ? 1 : 0));
    }
    return ok_status();
}

// One split's positions as the reader will decode them: the values to put (in
// coding order, on their grids) and the codes they give.
struct CodedPositions {
    uint16_t at[3], to[3];  // the child's, the parent's after the split
    bool moves = false;
    uint32_t child_grid = 0, parent_grid = 0;
    uint32_t value[6], shift[6];  // the child's 3 axes, then the parent's when it moves
};

// One coordinate on a grid of 2^grid steps: the rounded residual (zig-zag) into
// `value`, the decoded code into `out`; false when it would leave the box.
bool code_coordinate(uint16_t target, uint16_t predicted, uint32_t grid, uint32_t& value, uint16_t& out) {
    const int32_t r = int16_t(uint16_t(target - predicted));
    const int32_t rounded = grid == 0 ? r : (r + (1 << (grid - 1))) >> grid;
    const int32_t decoded = int32_t(target) + rounded * (1 << grid) - r;
    if (decoded < 0 || decoded > 65535) return false;
    value = pm::zigzag(uint16_t(rounded), uint16_t(0));
    out = uint16_t(decoded);
    return true;
}

// A position on a grid (a vertex's child position or its parent's after the
// split), axes in coding order; with a plane its axis is predicted from the two
// decoded before. False when a coordinate would leave the box on this grid.
bool code_position(const pm::FanPrediction& pred, const uint32_t order[3], const uint16_t target[3],
                   const uint16_t predicted2[3], bool plane_last, const uint16_t from[3], int64_t offset, int64_t scale,
                   uint32_t plane_shift, uint32_t grid, uint32_t* value, uint32_t* shift, uint16_t out[3]) {
    for (uint32_t i = 0; i < 3; ++i) {
        const uint32_t k = order[i];
        const bool plane = i == 2 && plane_last;
        const uint16_t predicted = plane ? pm::plane_coordinate(pred, from, out, offset, scale) : predicted2[k];
        const uint32_t scale_shift = plane ? plane_shift : pred.shift[k];
        if (!code_coordinate(target[k], predicted, grid, value[i], out[k])) return false;
        shift[i] = scale_shift > grid ? scale_shift - grid : 0;
    }
    return true;
}

// The child's position and the parent's move as residuals of their predictions;
// with a plane, the two other axes first, then the plane's axis. An intermediate
// position goes on the coarsest grid allowed (kCoarseFraction) that stays in the box.
CodedPositions code_positions(const pm::FanPrediction& pred, const uint16_t from[3], const uint16_t to[3],
                              const uint16_t at[3], bool moves, bool fan, uint32_t child_grid, uint32_t parent_grid) {
    CodedPositions c;
    uint32_t order[3] = {0, 1, 2};
    const bool plane = pred.axis < 3;
    if (plane) {
        pm::plane_axes(pred.axis, order[0], order[1]);
        order[2] = pred.axis;
    }
    c.child_grid = child_grid + 1;
    do --c.child_grid;
    while (!code_position(pred, order, at, pred.child, plane, from, pred.child_dot, 4, pred.axis_shift, c.child_grid,
                          c.value, c.shift, c.at));
    std::copy_n(from, 3, c.to);
    if (!moves) return c;
    uint16_t predicted[3];
    for (int k = 0; k < 3; ++k) {
        const uint16_t reflected = pm::reflect16(from[k], c.at[k]);
        predicted[k] = fan ? pm::parent_position(from[k], c.at[k], pred.parent_centroid[k]) : reflected;
    }
    const int64_t offset = plane ? pm::parent_plane_offset(pred, from, c.at) : 0;
    c.parent_grid = parent_grid + 1;
    do --c.parent_grid;
    while (!code_position(pred, order, to, predicted, plane, from, offset, pm::kParentPlaneScale,
                          pm::parent_plane_shift(pred), c.parent_grid, c.value + 3, c.shift + 3, c.to));
    c.moves = c.to[0] != from[0] || c.to[1] != from[1] || c.to[2] != from[2];
    if (!c.moves) c.parent_grid = 0;
    return c;
}

void put_positions(pm::SplitEncoder& values, const CodedPositions& c) {
    values.put(pm::kCtxChildCoarse, c.child_grid);
    if (c.moves) values.put(pm::kCtxParentCoarse, c.parent_grid);
    for (uint32_t i = 0; i < (c.moves ? 6u : 3u); ++i)
        values.put_scaled((i < 3 ? pm::kCtxChild0 : pm::kCtxParent0) + i % 3, c.value[i], c.shift[i]);
}

// The child's normal: a residual of its faces' normal after the split (fan form),
// else of the parent's.
void put_normal(SplitWriter& w, const pm::FanPrediction& pred, const uint16_t from[3], const uint16_t to[3],
                uint32_t parent, uint32_t child, bool fan) {
    const uint8_t* oct = w.z.oct.data();
    uint8_t predicted[2] = {oct[size_t(parent) * 2], oct[size_t(parent) * 2 + 1]};
    if (fan) pm::predict_normal(pred, from, to, w.axis_weight, predicted);
    for (int k = 0; k < 2; ++k)
        w.values.put(pm::kCtxNormal0 + uint32_t(k), pm::zigzag(oct[size_t(child) * 2 + k], predicted[k]));
}

// Split j's positions as codes: the parent's before (as the replayed level has
// it: an intermediate position is where its grid put it) and after, and the child's.
Status split_codes(const SplitWriter& w, size_t j, uint16_t from[3], uint16_t to[3], uint16_t at[3], bool& moves) {
    const VertexSplit& sp = w.pm.splits[j];
    const uint32_t child = uint32_t(w.pm.base_vertices + j);
    moves = false;
    for (int k = 0; k < 3; ++k) {
        from[k] = w.cur[size_t(sp.parent) * 3 + k];
        const uint16_t built_from = quantize16(sp.parent_from[k], w.z.lo[k], w.z.hi[k]);
        if (w.exact[sp.parent] && from[k] != built_from)
            return split_error(w.mesh, j, "moves its parent from elsewhere than it is");
        to[k] = quantize16(sp.parent_to[k], w.z.lo[k], w.z.hi[k]);
        moves |= to[k] != built_from;
        at[k] = w.z.q[size_t(child) * 3 + k];
    }
    return ok_status();
}

// Split j into the chunk's values and topology records, then onto the replay.
Status encode_split(SplitWriter& w, size_t j) {
    const VertexSplit& sp = w.pm.splits[j];
    const uint32_t child = uint32_t(w.pm.base_vertices + j), parent = sp.parent;
    prefetch_ahead(w, j);
    w.replay.corners_of(parent, w.parent_corners);
    const uint64_t mask = mask_of(w.pm, w.file_face, j, w.parent_corners);
    if (Status st = new_faces(w, j, child, parent); !st) return st;
    uint32_t ring[64];
    uint8_t fan_at[64];
    const FanSplit fan = fan_split(w.replay, parent, w.parent_corners, w.faces, mask, ring, fan_at);
    if (fan.swapped) {
        std::rotate(w.faces.begin(), w.faces.begin() + 3, w.faces.end());
        std::swap(w.file_face[w.face], w.file_face[w.face + 1]);
    }
    uint16_t from[3], to[3], at[3];
    bool builder_moves = false;
    if (Status st = split_codes(w, j, from, to, at, builder_moves); !st) return st;
    const uint32_t form = fan.length == 0 ? pm::kTopoGeneral : pm::kTopoFan;
    pm::FanPrediction pred{{from[0], from[1], from[2]}, {0, 0, 0}, {0, 0, 0}};
    if (form == pm::kTopoFan) {
        // The plane through the parent: its normal (when the file has normals).
        int64_t plane[3];
        pm::plane_normal(&w.z.oct[size_t(parent) * 2], w.plane_weight, plane);
        pm::predict_fan(w.cur.data(), ring, fan.fan, fan.start, fan.length, from, w.normals ? plane : nullptr, pred);
    }
    const CodedPositions coded =
        code_positions(pred, from, to, at, builder_moves, form == pm::kTopoFan, w.child_grid[j], w.parent_grid[j]);
    w.values.put(pm::kCtxKind, form * 2 + (coded.moves ? 1 : 0));
    const uint32_t error = error_bits(round_up_coarse(sp.error));
    if (error > w.previous_error) return split_error(w.mesh, j, "has a larger error than the split before it");
    w.values.put(pm::kCtxErrorStep, (w.previous_error - error) >> 16);
    w.previous_error = error;
    if (form == pm::kTopoGeneral) {
        if (Status st = put_general_topology(w, j, mask, parent); !st) return st;
    } else {
        w.values.put(pm::kCtxFanStart, fan.start);
        w.values.put(pm::kCtxFanLength, fan.length - 1);
    }
    put_positions(w.values, coded);
    if (w.normals) put_normal(w, pred, from, coded.to, parent, child, form == pm::kTopoFan);
    // (parent_corners are still the parent's: nothing changed the replay since.)
    w.moved.resize(w.parent_corners.size());
    const size_t moving = size_t(std::popcount(mask));
    if (!w.replay.apply_mask(parent, child, mask, moving, w.parent_corners.data(), w.parent_corners.size(),
                             w.moved.data()) ||
        moving != w.pm.patch_begin[j + 1] - w.pm.patch_begin[j])
        return split_error(w.mesh, j, "index patches do not replay");
    w.replay.add_faces(w.face, w.faces);
    w.face += sp.face_count;
    for (int k = 0; k < 3; ++k) {
        w.cur[size_t(parent) * 3 + k] = coded.to[k];
        w.cur[size_t(child) * 3 + k] = coded.at[k];
    }
    if (builder_moves) w.exact[parent] = std::equal(to, to + 3, coded.to);
    w.exact[child] = std::equal(at, at + 3, coded.at);
    return ok_status();
}

// One SPLT payload: splits [first, first + count). On one thread: a second one for
// the topology did not pay (bench/RESULTS.md, 2026-11-26).
Result<std::vector<uint8_t>> encode_chunk(SplitWriter& w, size_t first, size_t count) {
    size_t chunk_faces = 0;
    for (size_t j = first; j < first + count; ++j) chunk_faces += w.pm.splits[j].face_count;
    w.values.clear();
    w.topo.clear();
    // All parents of the chunk first: the reader prefetches their data splits ahead.
    // Each as the step from the one before (0 before the first): inside a round
    // of a batch they ascend (split_order.h).
    uint32_t previous = 0;
    for (size_t j = first; j < first + count; ++j) {
        const uint32_t parent = w.pm.splits[j].parent;
        w.values.put(pm::kCtxParentDelta, pm::zigzag(parent, previous));
        previous = parent;
    }
    for (size_t j = first; j < first + count; ++j)
        if (Status st = encode_split(w, j); !st) return st.error();
    std::vector<uint8_t> payload;
    put_u32(payload, uint32_t(first));
    put_u32(payload, uint32_t(count));
    put_u32(payload, uint32_t(chunk_faces));
    std::vector<uint8_t> coded;
    w.values.finish(coded, w.sizes);
    if (w.sizes) {
        // first, count, faces, the two payload sizes; the section's tag .. length and checksum.
        w.sizes->header_bits += 8.0 * (5 * 4 + 12 + 4);
        w.sizes->topology_bits += 8.0 * double(w.topo.size());
        w.sizes->splits += count;
    }
    put_u32(payload, uint32_t(coded.size()));
    payload.insert(payload.end(), coded.begin(), coded.end());
    put_u32(payload, uint32_t(w.topo.size()));
    payload.insert(payload.end(), w.topo.begin(), w.topo.end());
    return payload;
}

Result<StructureSections> encode_structure(const Mesh& mesh, const ProgressiveBuild& pm, const LodOptions& options,
                                           pm::SplitSizes* sizes) {
    StructureSections out;
    const Quantized z = quantize(pm, options.normals);
    const size_t ns = pm.splits.size(), chunk = std::max<size_t>(options.chunk_splits, 1);
    out.info = info_section(mesh, pm, z, options.normals, chunk);
    SplitWriter w(mesh, pm, z, options.normals);
    w.sizes = sizes;
    plan_grids(w, options.coarse_intermediate);
    out.base = base_section(pm, z, w.replay);
    for (size_t first = 0; first < ns; first += chunk) {
        auto payload = encode_chunk(w, first, std::min(chunk, ns - first));
        if (!payload) return payload.error();
        out.chunks.push_back(std::move(*payload));
    }
    return out;
}

}  // namespace

Result<std::vector<uint8_t>> encode_bpm(std::span<const Mesh> meshes, const LodOptions& options,
                                        pm::SplitSizes* sizes) {
    if (meshes.empty()) return input_error("lod: no meshes to write");
    if (meshes.size() > 65535) return input_error("lod: too many structures (" + std::to_string(meshes.size()) + ")");
    std::vector<StructureSections> parts;
    for (const Mesh& m : meshes) {
        auto pm = build_progressive_mesh(m, options);
        if (!pm) return pm.error();
        auto sec = encode_structure(m, *pm, options, sizes);
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

Status write_bpm_from_meshes(const std::string& path, std::span<const Mesh> meshes, const LodOptions& options,
                             pm::SplitSizes* sizes) {
    auto bytes = encode_bpm(meshes, options, sizes);
    if (!bytes) return bytes.error();
    return write_file_atomically(path, *bytes);
}

}  // namespace body::lod
