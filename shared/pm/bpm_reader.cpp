// See bpm_reader.h. Progressive meshes after H. Hoppe, "Progressive meshes",
// SIGGRAPH 1996; the BASE section's codecs are meshoptimizer's (A. Kapoulkine,
// meshopt_decodeVertexBuffer / meshopt_decodeIndexBuffer).
#include "shared/pm/bpm_reader.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "shared/atomic_file.h"
#include "shared/input_file.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/draw_order.h"
#include "shared/pm/prediction.h"
#include "shared/pm/split_codec.h"

namespace body::pm {

BpmStream::BpmStream(std::string source_name, FaceOrder order) : source_(std::move(source_name)), order_(order) {}

namespace {

std::string where_of(const std::string& source, uint32_t tag, uint32_t structure, size_t offset) {
    return source + ": section " + tag_name(tag) + " of structure " + std::to_string(structure) + " at byte " +
           std::to_string(offset);
}

}  // namespace

Status BpmStream::feed(std::span<const uint8_t> bytes) {
    if (failed_) return input_error(failure_);
    paused_ = false;
    pending_.insert(pending_.end(), bytes.begin(), bytes.end());
    auto fail = [&](std::string message) -> Status {
        failed_ = true;
        failure_ = std::move(message);
        return input_error(failure_);
    };
    size_t pos = 0;
    if (!header_done_) {
        if (pending_.size() < kFileHeaderSize) return ok_status();
        const uint8_t* h = pending_.data();
        if (std::memcmp(h, kMagic, 4) != 0)
            return fail(source_ + ": file header at byte 0: not a .bpm file (bad magic)");
        if (crc32({h, 12}) != get_u32(h + 12)) return fail(source_ + ": file header at byte 0: checksum mismatch");
        if (get_u16(h + 4) != kVersion)
            return fail(source_ + ": file header at byte 4: unsupported version " + std::to_string(get_u16(h + 4)));
        if (get_u16(h + 6) != 0) return fail(source_ + ": file header at byte 6: flags must be 0");
        declared_structures_ = get_u32(h + 8);
        if (declared_structures_ > 65535) return fail(source_ + ": file header at byte 8: too many structures");
        header_done_ = true;
        pos = kFileHeaderSize;
    }
    while (pending_.size() - pos >= kSectionHeaderSize) {
        const uint8_t* s = pending_.data() + pos;
        const size_t offset = consumed_ + pos;
        const uint32_t tag = get_u32(s), structure = get_u16(s + 4), length = get_u32(s + 8);
        const std::string where = where_of(source_, tag, structure, offset);
        if (complete_) return fail(where + ": data after the END section");
        if (tag != kTagInfo && tag != kTagBase && tag != kTagSplits && tag != kTagEnd)
            return fail(where + ": unknown section tag");
        if (get_u16(s + 6) != 0)
            return fail(where + ": reserved field (byte " + std::to_string(offset + 6) + ") not 0");
        if (length > (1u << 30)) return fail(where + ": section length " + std::to_string(length) + " too large");
        // Nothing more wanted: stop before the splits (the bytes are read again later).
        if (tag == kTagSplits && !wants_more()) paused_ = true;
        if (paused_) break;
        const size_t total = kSectionHeaderSize + size_t(length) + kSectionTrailerSize;
        if (pending_.size() - pos < total) break;
        if (crc32({s, kSectionHeaderSize + length}) != get_u32(s + kSectionHeaderSize + length))
            return fail(where + ": checksum mismatch");
        Status st = parse_section(tag, structure, {s + kSectionHeaderSize, length}, offset);
        if (!st) return fail(st.error().message);
        if (parked_.offset == offset) {  // stopped inside: this section is read again on resuming
            paused_ = true;
            break;
        }
        pos += total;
    }
    consumed_ += pos;
    // The batch order's arrays (28 bytes a face of the largest batch) live for one
    // feed: a stream waiting for bytes holds none.
    for (auto& m : meshes_) m->order_scratch_.release_batch_arrays();
    if (paused_) {
        std::vector<uint8_t>().swap(pending_);  // a paused stream holds no bytes
        release_scratch();
        // Nor decoding state: rebuilt from the drawn arrays when its next split decodes.
        for (auto& m : meshes_) m->park_decoding_state();
        return ok_status();
    }
    pending_.erase(pending_.begin(), pending_.begin() + ptrdiff_t(pos));
    // Thousands of streams: a section's worth of capacity kept by each adds up.
    if (pending_.empty()) std::vector<uint8_t>().swap(pending_);
    if (complete_) release_scratch();
    return ok_status();
}

void BpmStream::release_scratch() {
    std::vector<uint32_t>().swap(split_parents_);
    std::vector<uint32_t>().swap(decoded_indices_);
    for (auto& m : meshes_) m->order_scratch_ = {};
}

void BpmStream::set_wanted_splits(size_t structure, size_t splits) {
    if (structure < wanted_.size()) wanted_[structure] = splits;
}

void BpmStream::set_wanted_splits_all(size_t splits) {
    default_wanted_ = splits;
    std::fill(wanted_.begin(), wanted_.end(), splits);
}

size_t BpmStream::split_limit(size_t structure) const {
    const ProgressiveMesh& m = *meshes_[structure];
    const size_t want = std::min(wanted_[structure], m.split_count_);
    if (!m.batched() || want == 0) return want;
    // Batch boundaries: a level inside a batch is drawable only while it arrives.
    return *std::lower_bound(m.batch_levels_.begin(), m.batch_levels_.end(), uint32_t(want));
}

bool BpmStream::wants_more_except(size_t structure) const {
    if (complete_) return false;
    if (!header_done_ || meshes_.size() < declared_structures_) return true;
    for (size_t i = 0; i < meshes_.size(); ++i)
        if (i != structure && (!meshes_[i]->base_ready_ || meshes_[i]->decoded_splits_ < split_limit(i))) return true;
    return false;
}

bool BpmStream::wants_more() const { return wants_more_except(SIZE_MAX); }

Status BpmStream::finish() const {
    if (failed_) return input_error(failure_);
    if (complete_ && !pending_.empty())
        return input_error(source_ + ": byte " + std::to_string(consumed_) + ": " + std::to_string(pending_.size()) +
                           " bytes after the END section");
    if (complete_) return ok_status();
    if (!header_done_)
        return input_error(source_ + ": file header at byte 0: truncated (" + std::to_string(pending_.size()) +
                           " of 16 bytes)");
    if (pending_.size() >= kSectionHeaderSize) {
        const uint32_t tag = get_u32(pending_.data()), structure = get_u16(pending_.data() + 4);
        return input_error(
            where_of(source_, tag, structure, consumed_) + ": truncated (" + std::to_string(pending_.size()) + " of " +
            std::to_string(kSectionHeaderSize + get_u32(pending_.data() + 8) + kSectionTrailerSize) + " bytes)");
    }
    return input_error(source_ + ": truncated at byte " + std::to_string(consumed_ + pending_.size()) +
                       ": the END section is missing");
}

Status BpmStream::parse_section(uint32_t tag, uint32_t structure, std::span<const uint8_t> payload, size_t offset) {
    const std::string where = where_of(source_, tag, structure, offset);
    if (tag == kTagEnd) {
        ByteReader r(payload);
        uint32_t count = 0;
        if (!r.u32(count) || count != meshes_.size() || count != declared_structures_)
            return input_error(where + ": structure count does not match");
        for (auto& m : meshes_) {
            if (m->decoded_splits_ != m->split_count_ || !m->base_ready_)
                return input_error(where + ": structure '" + m->name_ + "' is incomplete");
        }
        complete_ = true;
        return ok_status();
    }
    if (tag == kTagInfo) {
        if (structure != meshes_.size() || structure >= declared_structures_)
            return input_error(where + ": INFO out of order");
        return parse_info(payload, where);
    }
    if (structure >= meshes_.size()) return input_error(where + ": section before the structure's INFO");
    ProgressiveMesh& m = *meshes_[structure];
    if (tag == kTagBase) {
        if (m.base_ready_) return input_error(where + ": second BASE section");
        return parse_base(m, payload, where);
    }
    if (!m.base_ready_) return input_error(where + ": SPLT before BASE");
    return parse_splits(structure, payload, offset, where);
}

Status BpmStream::parse_info(std::span<const uint8_t> payload, const std::string& where) {
    InfoRecord info;
    if (const char* reason = read_info(payload, info)) return input_error(where + ": " + reason);
    auto m = std::make_unique<ProgressiveMesh>();
    const std::span<const uint8_t> name = info.name;
    const uint32_t flags = info.flags, bv = info.base_vertices, bf = info.base_faces, splits = info.splits,
                   faces = info.faces, chunk = info.chunk_splits;
    const uint64_t vertices = uint64_t(bv) + splits;
    m->name_.assign(name.begin(), name.end());
    m->color_ = Vec3f(info.color[0], info.color[1], info.color[2]);
    m->bbox_min_ = Vec3f(info.box_min[0], info.box_min[1], info.box_min[2]);
    m->bbox_max_ = Vec3f(info.box_max[0], info.box_max[1], info.box_max[2]);
    m->has_normals_ = flags & 1;
    for (int k = 0; k < 3; ++k) m->step_[k] = quantization_step(m->bbox_min_[k], m->bbox_max_[k]);
    m->base_vertices_ = bv;
    m->base_faces_ = bf;
    m->split_count_ = splits;
    m->face_count_ = faces;
    m->chunk_splits_ = chunk;
    // Every array, the renderer's too, grows with the sections (grow_decoded).
    m->parent_bytes_ = vertices <= (uint64_t(1) << 24) ? 3 : 4;
    m->move_count_ = 0;
    m->patch_corners_.clear();
    m->corner_bytes_ = uint64_t(faces) * 3 <= (uint64_t(1) << 24) ? 3 : 4;
    m->replay_.clear(vertices);
    if (order_ == FaceOrder::Batched && splits > 0) m->batch_levels_ = batch_levels(bv, splits);
    m->grow_decoded(0, bf);
    m->face_sample_[0] = bf;
    meshes_.push_back(std::move(m));
    wanted_.push_back(default_wanted_);
    return ok_status();
}

Status BpmStream::parse_base(ProgressiveMesh& m, std::span<const uint8_t> payload, const std::string& where) {
    ByteReader r(payload);
    uint32_t vbytes = 0, ibytes = 0;
    std::span<const uint8_t> vbuf, ibuf;
    if (!r.u32(vbytes) || !r.bytes(vbytes, vbuf) || !r.u32(ibytes) || !r.bytes(ibytes, ibuf) || r.left() != 0)
        return input_error(where + ": BASE payload sizes do not add up");
    std::vector<BaseVertex> verts(m.base_vertices_);
    if (meshopt_decodeVertexBuffer(verts.data(), verts.size(), sizeof(BaseVertex), vbuf.data(), vbuf.size()) != 0)
        return input_error(where + ": vertex data does not decode");
    decoded_indices_.resize(m.base_faces_ * 3);
    if (meshopt_decodeIndexBuffer(decoded_indices_.data(), decoded_indices_.size(), 4, ibuf.data(), ibuf.size()) != 0)
        return input_error(where + ": index data does not decode");
    for (uint32_t v : decoded_indices_)
        if (v >= m.base_vertices_) return input_error(where + ": base index " + std::to_string(v) + " out of range");
    for (size_t v = 0; v < verts.size(); ++v) {
        for (int k = 0; k < 3; ++k) {
            m.qpos_[v * 3 + k] = verts[v].q[k];
            m.positions_[v * 3 + k] = verts[v].q[k];
        }
        m.qoct_[v * 2] = verts[v].oct[0];
        m.qoct_[v * 2 + 1] = verts[v].oct[1];
        if (m.has_normals_) std::copy_n(verts[v].oct, 2, &m.normals_[v * 2]);
    }
    if (m.batched())
        for (size_t v = 0; v < verts.size(); ++v) m.vertex_slot_[v] = uint32_t(v);
    std::copy(decoded_indices_.begin(), decoded_indices_.end(), m.indices_.begin());
    m.replay_.add_faces(0, decoded_indices_);
    if (m.batched())
        for (size_t f = 0; f < m.base_faces_; ++f) m.face_slot_[f] = uint32_t(f);
    m.decoded_faces_ = m.base_faces_;
    m.base_ready_ = true;
    m.dirty_vertices_.add(0, m.base_vertices_);
    m.dirty_indices_.add(0, m.base_faces_ * 3);
    if (m.split_count_ == 0) m.release_decoding_state();
    return ok_status();
}

namespace {

// What the splits of one SPLT chunk decode against: the replay and the codes at
// the finest decoded level (the structure's decoding state) and the box's weights.
struct ChunkContext {
    SplitReplay& replay;
    const uint16_t* qpos;  // 3 per vertex
    const uint8_t* qoct;   // 2 per vertex
    bool normals;
    int32_t axis_weight[3], plane_weight[3];
    // Batched order: per vertex its draw number, per face its draw place
    // (record_split reads both around each parent; null in refinement order).
    const uint32_t *vertex_slot = nullptr, *face_slot = nullptr;
};

// One split as it decodes: its topology (the parent's corners, those moving to
// the child, the new faces), its predictions and its decoded codes.
struct DecodedSplit {
    uint32_t child = 0, parent = 0;
    uint32_t corners[64];
    size_t corner_count = 0;
    uint64_t mask = 0;
    uint32_t moving = 0;  // popcount(mask): the corners moving to the child
    uint32_t faces = 0, faces_at[9];
    uint32_t fan = 0;               // fan form: the size of the parent's fan
    uint16_t from[3], q[3], to[3];  // the parent before and after, the child
    uint8_t oct[2];
    FanPrediction pred;  // the general form: child at the parent, no scaling (decode_topology)
};

// The replay is bound by memory latency (a parent is anywhere in the mesh): the
// data of the splits a few steps ahead is pulled into the cache in stages.
[[gnu::always_inline]] inline void prefetch_ahead(const ChunkContext& c, const std::vector<uint32_t>& parents,
                                                  uint32_t i) {
    constexpr uint32_t kAhead0 = 32, kAhead1 = 20, kAhead2 = 12, kAhead3 = 6;
    const size_t count = parents.size();
    if (i + kAhead0 < count) c.replay.prefetch(parents[i + kAhead0], 0);
    if (i + kAhead1 < count) {
        const uint32_t p = parents[i + kAhead1];
        c.replay.prefetch(p, 1);
        prefetch(&c.qpos[size_t(p) * 3]);
        prefetch(&c.qoct[size_t(p) * 2]);
        if (c.vertex_slot) prefetch(&c.vertex_slot[p]);
    }
    if (i + kAhead2 < count) c.replay.prefetch(parents[i + kAhead2], 2, nullptr, nullptr, c.face_slot);
    if (i + kAhead3 < count) c.replay.prefetch(parents[i + kAhead3], 3, c.qpos, c.vertex_slot);
}

// Fan form (a manifold split): the fan faces from ring[start] to ring[start + length]
// move to the child; the new faces are (c, p, ring[start]), (c, ring[start + length], p).
[[gnu::always_inline]] inline const char* decode_fan(const ChunkContext& c, SplitDecoder::Cursor& values,
                                                     DecodedSplit& s) {
    uint32_t ring[64];
    uint8_t fan_at[64];
    s.fan = uint32_t(c.replay.ordered_fan(s.corners, s.corner_count, ring, fan_at));
    const uint32_t start = values.get(kCtxFanStart), length = values.get(kCtxFanLength) + 1;
    if (s.fan == 0 || start >= s.fan || length >= s.fan) return "fan split of a vertex without such a fan";
    uint32_t at = start;
    for (uint32_t t = 0; t < length; ++t, at = at + 1 == s.fan ? 0 : at + 1) s.mask |= uint64_t(1) << fan_at[at];
    s.moving = length;  // fan_at names each fan face once
    s.faces = 2;
    const uint32_t f[6] = {s.child, s.parent, ring[start], s.child, ring[at], s.parent};
    std::copy_n(f, 6, s.faces_at);
    // The plane through the parent: its normal (when the file has normals).
    int64_t plane[3];
    plane_normal(&c.qoct[size_t(s.parent) * 2], c.plane_weight, plane);
    predict_fan(c.qpos, ring, s.fan, start, length, s.from, c.normals ? plane : nullptr, s.pred);
    return nullptr;
}

// General form: the patch mask, then each new face's third vertex as a neighbour
// number over the parent's corners before the split, from the topology bytes.
[[gnu::always_inline]] inline const char* decode_general(const ChunkContext& c, ByteReader& topo, DecodedSplit& s) {
    uint64_t head = 0;
    if (!topo.varint(head)) return "topology record truncated";
    s.faces = uint32_t(head & 3);
    s.mask = head >> 2;
    s.moving = uint32_t(std::popcount(s.mask));
    for (uint32_t f = 0; f < s.faces && f < 3; ++f) {
        uint64_t code = 0;
        if (!topo.varint(code) || (code >> 1) >= 2 * s.corner_count) return "a new face names a missing neighbour";
        const uint32_t third = c.replay.neighbour(s.corners, size_t(code >> 1));
        uint32_t* t = s.faces_at + 3 * f;
        t[0] = s.child;
        t[1] = (code & 1) ? third : s.parent;
        t[2] = (code & 1) ? s.parent : third;
    }
    return nullptr;
}

// The split's topology in its kind's form; an error text, or nullptr.
[[gnu::always_inline]] inline const char* decode_topology(const ChunkContext& c, SplitDecoder::Cursor& values,
                                                          ByteReader& topo, uint32_t form, DecodedSplit& s) {
    s.corner_count = c.replay.corners_of(s.parent, s.corners, 64);
    if (s.corner_count == SIZE_MAX) return "parent has more than 64 corners";
    for (int k = 0; k < 3; ++k) {
        s.from[k] = c.qpos[size_t(s.parent) * 3 + k];
        s.pred.child[k] = s.from[k];
        s.pred.parent_centroid[k] = 0;
        s.pred.shift[k] = 0;
    }
    if (form == kTopoFan) return decode_fan(c, values, s);
    if (form == kTopoGeneral) return decode_general(c, topo, s);
    return "unknown split kind";
}

// One coordinate on a grid of 2^grid steps: the residual's high part entropy
// coded, its low bits below the predicted scale (shift - grid) raw.
[[gnu::always_inline]] inline uint16_t decode_coordinate(SplitDecoder::Cursor& values, uint32_t context,
                                                         uint16_t predicted, uint32_t shift, uint32_t grid) {
    const uint32_t z = values.get_scaled(context, shift > grid ? shift - grid : 0);
    return uint16_t(predicted + (uint32_t(unzigzag(uint16_t(z), uint16_t(0))) << grid));
}

// The child's position and the parent's move (0 to 1 positions), as residuals of
// their predictions on their grids; with a plane, its axis last.
[[gnu::always_inline]] inline void decode_positions(SplitDecoder::Cursor& values, bool moves, uint32_t child_grid,
                                                    uint32_t parent_grid, DecodedSplit& s) {
    const FanPrediction& pred = s.pred;
    uint32_t order[3] = {0, 1, 2};
    if (pred.axis < 3) {
        plane_axes(pred.axis, order[0], order[1]);
        order[2] = pred.axis;
    }
    for (uint32_t i = 0; i < 2; ++i)
        s.q[order[i]] =
            decode_coordinate(values, kCtxChild0 + i, pred.child[order[i]], pred.shift[order[i]], child_grid);
    if (pred.axis < 3)
        s.q[order[2]] =
            decode_coordinate(values, kCtxChild0 + 2, plane_coordinate(pred, s.from, s.q, pred.child_dot, 4),
                              pred.axis_shift, child_grid);
    else
        s.q[2] = decode_coordinate(values, kCtxChild0 + 2, pred.child[2], pred.shift[2], child_grid);
    for (int k = 0; k < 3; ++k) s.to[k] = s.from[k];
    if (!moves) return;
    for (uint32_t i = 0; i < (pred.axis < 3 ? 2u : 3u); ++i) {
        const uint32_t k = order[i];
        const uint16_t reflected = reflect16(s.from[k], s.q[k]);
        const uint16_t predicted = s.fan != 0 ? parent_position(s.from[k], s.q[k], pred.parent_centroid[k]) : reflected;
        s.to[k] = decode_coordinate(values, kCtxParent0 + i, predicted, pred.shift[k], parent_grid);
    }
    if (pred.axis < 3) {
        const int64_t offset = parent_plane_offset(pred, s.from, s.q);
        s.to[order[2]] =
            decode_coordinate(values, kCtxParent0 + 2, plane_coordinate(pred, s.from, s.to, offset, kParentPlaneScale),
                              parent_plane_shift(pred), parent_grid);
    }
}

// The child's normal: predicted from its faces after the split (fan form), else
// the parent's; the parent's when the file has none.
[[gnu::always_inline]] inline void decode_normal(const ChunkContext& c, SplitDecoder::Cursor& values, DecodedSplit& s) {
    s.oct[0] = c.qoct[size_t(s.parent) * 2];
    s.oct[1] = c.qoct[size_t(s.parent) * 2 + 1];
    if (!c.normals) return;
    if (s.fan != 0) predict_normal(s.pred, s.from, s.to, c.axis_weight, s.oct);
    for (int k = 0; k < 2; ++k) s.oct[k] = unzigzag(uint8_t(values.get(kCtxNormal0 + uint32_t(k))), s.oct[k]);
}

// A SPLT payload's framing.
struct ChunkHeader {
    uint32_t first = 0, count = 0, new_faces = 0;
    std::span<const uint8_t> values, topology;
};

bool read_chunk_header(std::span<const uint8_t> payload, ChunkHeader& h) {
    ByteReader r(payload);
    uint32_t vbytes = 0, tbytes = 0;
    return r.u32(h.first) && r.u32(h.count) && r.u32(h.new_faces) && r.u32(vbytes) && r.bytes(vbytes, h.values) &&
           r.u32(tbytes) && r.bytes(tbytes, h.topology) && r.left() == 0;
}

}  // namespace

void BpmStream::record_split(ProgressiveMesh& m, size_t j, uint32_t parent, uint32_t child,
                             std::span<const uint32_t> faces, std::span<const uint32_t> moved, const uint16_t from[3],
                             const uint16_t to[3], const uint16_t q[3], const uint8_t oct[2], uint16_t error_high) {
    m.replay_.add_faces(m.decoded_faces_, faces);
    const bool batched = m.batched();
    uint32_t* const face_entries = &m.indices_[m.decoded_faces_ * 3];
    if (batched) {
        // The child keeps its number until its batch is complete (order_batch);
        // the older vertices are in draw order.
        m.vertex_slot_[child] = child;
        for (size_t i = 0; i < faces.size(); ++i) face_entries[i] = m.vertex_slot_[faces[i]];
        for (size_t f = m.decoded_faces_; f < m.decoded_faces_ + faces.size() / 3; ++f) m.face_slot_[f] = uint32_t(f);
        ProgressiveMesh::store_le(&m.split_children_bytes_[j * m.parent_bytes_], child, m.parent_bytes_);
    } else {
        std::copy(faces.begin(), faces.end(), face_entries);
    }
    m.decoded_faces_ += faces.size() / 3;
    m.face_count_bits_[j / 32] |= uint64_t(faces.size() / 3) << (j % 32 * 2);
    if ((j + 1) % 64 == 0) m.face_sample_[(j + 1) / 64] = uint32_t(m.decoded_faces_);
    if (m.error_highs_.empty() || error_high != m.error_highs_.back()) {
        m.error_levels_.push_back(uint32_t(j));
        m.error_highs_.push_back(error_high);
    }
    const size_t at = m.patch_corners_.size(), w = m.corner_bytes_;
    m.patch_corners_.resize(at + moved.size() * w);
    for (size_t i = 0; i < moved.size(); ++i) {
        // The replay numbers faces as the file does; indices_ holds them in draw order.
        const uint32_t c = batched ? m.face_slot_[moved[i] / 3] * 3 + moved[i] % 3 : moved[i];
        ProgressiveMesh::store_le(&m.patch_corners_[at + i * w], c, w);
    }
    m.patch_count_[j] = uint8_t(moved.size());
    if (j % 64 == 0) m.move_rank_[j / 64] = uint32_t(m.move_count_);
    if ((from[0] ^ to[0]) | (from[1] ^ to[1]) | (from[2] ^ to[2])) {
        m.move_bits_[j / 64] |= uint64_t(1) << (j % 64);
        for (int k = 0; k < 3; ++k) m.moves_[m.move_count_ * 3 + size_t(k)] = uint16_t(from[k] ^ to[k]);
        ++m.move_count_;
    }
    for (int k = 0; k < 3; ++k) {
        m.qpos_[size_t(child) * 3 + k] = q[k];
        m.qpos_[size_t(parent) * 3 + k] = to[k];
        m.positions_[size_t(child) * 3 + k] = q[k];
    }
    m.qoct_[size_t(child) * 2] = oct[0];
    m.qoct_[size_t(child) * 2 + 1] = oct[1];
    if (m.has_normals_) std::copy_n(oct, 2, &m.normals_[size_t(child) * 2]);
    ProgressiveMesh::store_le(&m.split_parents_bytes_[j * m.parent_bytes_], m.vertex_in_draw_order(parent),
                              m.parent_bytes_);
}

Status BpmStream::parse_splits(size_t structure, std::span<const uint8_t> payload, size_t offset,
                               const std::string& where) {
    ProgressiveMesh& m = *meshes_[structure];
    ChunkHeader h;
    if (!read_chunk_header(payload, h)) return input_error(where + ": SPLT payload sizes do not add up");
    // A section stopped part-way (decoding on demand) goes on where it stopped.
    Parked at = parked_.offset == offset ? parked_ : Parked{};
    parked_.offset = SIZE_MAX;
    const uint32_t first = h.first, count = h.count;
    const size_t faces_before = m.decoded_faces_ - at.face_cursor;
    if (first + at.next != m.decoded_splits_ || count == 0 || count > m.split_count_ - first ||
        h.new_faces > m.face_count_ - faces_before)
        return input_error(where + ": split range " + std::to_string(first) + "+" + std::to_string(count) +
                           " does not follow split " + std::to_string(m.decoded_splits_));
    // Where to stop: the structure's limit, unless another structure wants more.
    const uint32_t stop =
        wants_more_except(structure)
            ? count
            : uint32_t(std::clamp<size_t>(split_limit(structure), first + at.next + 1, size_t(first) + count) - first);
    m.unpark_decoding_state();  // a structure paused before: its state back first
    // A split adds 1 to 3 faces: grown for what is decoded now, not the whole section.
    if (whole_file_) {
        m.grow_decoded(m.split_count_, m.face_count_);
        m.replay_.hold_vertices(m.base_vertices_ + m.split_count_);
    }
    m.grow_decoded(size_t(first) + stop,
                   std::min(faces_before + h.new_faces, m.decoded_faces_ + 3 * size_t(stop - at.next)));
    SplitDecoder decoder;
    if (!decoder.init(h.values)) return input_error(where + ": split value tables do not decode");
    SplitDecoder::Cursor values = decoder.begin();
    // The chunk's parents come first (the loop below prefetches their data).
    std::vector<uint32_t>& parents = split_parents_;
    parents.resize(count);
    uint32_t previous = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t child = uint32_t(m.base_vertices_ + first + i);
        const uint32_t parent = unzigzag(values.get(kCtxParentDelta), previous);
        if (parent >= child || values.past_end())
            return input_error(where + ": split " + std::to_string(first + i) + ": parent out of range");
        parents[i] = previous = parent;
    }
    ByteReader topo(h.topology);
    size_t face_cursor = at.face_cursor;
    uint32_t previous_error_bits = at.error_bits;
    if (at.next == 0) {
        const float previous_error = first == 0 ? INFINITY : m.error_at(first - 1);
        std::memcpy(&previous_error_bits, &previous_error, 4);
    } else {
        std::span<const uint8_t> skipped;
        (void)topo.bytes(at.topology_at, skipped);
        values.rans_pos = at.rans_pos;
        values.bit_pos = at.bit_pos;
        values.state = at.state;
        values.other_state = at.other_state;
    }
    // Everything below runs per split: no allocation (the message is built on failure only).
    // Geometric growth: reserving the exact need per section would copy the whole
    // array at every section (quadratic in the file's size).
    if (const size_t need = m.patch_corners_.size() + size_t(stop - at.next) * 4 * m.corner_bytes_;
        need > m.patch_corners_.capacity())
        m.patch_corners_.reserve(std::max(need, 2 * m.patch_corners_.capacity()));
    ChunkContext ctx{m.replay_, m.qpos_.data(), m.qoct_.data(), m.has_normals_, {}, {}};
    if (m.batched()) {
        ctx.vertex_slot = m.vertex_slot_.data();
        ctx.face_slot = m.face_slot_.data();
    }
    const float box_lo[3] = {m.bbox_min_.x, m.bbox_min_.y, m.bbox_min_.z},
                box_hi[3] = {m.bbox_max_.x, m.bbox_max_.y, m.bbox_max_.z};
    normal_axis_weights(box_lo, box_hi, ctx.axis_weight);
    plane_axis_weights(box_lo, box_hi, ctx.plane_weight);
    uint32_t moved[64];
    for (uint32_t i = at.next; i < stop; ++i) {
        prefetch_ahead(ctx, parents, i);
        const size_t j = first + i;
        DecodedSplit s;
        s.child = uint32_t(m.base_vertices_ + j);
        s.parent = parents[i];
        auto fail = [&](const char* what) { return input_error(where + ": split " + std::to_string(j) + ": " + what); };
        const uint32_t kind = values.get(kCtxKind);
        // Errors are non-increasing by construction: each is a step down from the previous.
        const uint32_t error_step = values.get(kCtxErrorStep);
        if (error_step > (previous_error_bits >> 16)) return fail("error not monotonic");
        previous_error_bits -= error_step << 16;
        if (const char* error = decode_topology(ctx, values, topo, kind >> 1, s)) return fail(error);
        if (s.faces == 0 || face_cursor + s.faces > h.new_faces) return fail("face count out of range");
        const uint32_t child_grid = values.get(kCtxChildCoarse);
        const uint32_t parent_grid = (kind & 1) ? values.get(kCtxParentCoarse) : 0;
        if (child_grid > kMaxCoarseShift || parent_grid > kMaxCoarseShift) return fail("position grid out of range");
        decode_positions(values, kind & 1, child_grid, parent_grid, s);
        decode_normal(ctx, values, s);
        if (values.past_end()) return fail("values truncated");
        // Index patches first (on the level before the split), then the new faces.
        if (!m.replay_.apply_mask(s.parent, s.child, s.mask, s.moving, s.corners, s.corner_count, moved))
            return fail("patch mask names a missing corner");
        record_split(m, j, s.parent, s.child, {s.faces_at, s.faces * 3}, {moved, s.moving}, s.from, s.to, s.q, s.oct,
                     uint16_t(previous_error_bits >> 16));  // the low half is 0
        face_cursor += s.faces;
        if (m.batched() && j + 1 == m.batch_levels_[m.ordered_batches_]) m.order_batch(j + 1);
    }
    const size_t first_child = m.base_vertices_ + first;
    m.dirty_vertices_.add(first_child + at.next, first_child + stop);
    m.dirty_indices_.add((m.decoded_faces_ - (face_cursor - at.face_cursor)) * 3, m.decoded_faces_ * 3);
    m.decoded_splits_ = size_t(first) + stop;
    if (stop < count) {  // nothing more wanted: the decoder's place kept, the section read again later
        parked_ = Parked{offset,          stop,           face_cursor,  topo.offset(),     previous_error_bits,
                         values.rans_pos, values.bit_pos, values.state, values.other_state};
        return ok_status();
    }
    if (face_cursor != h.new_faces || topo.left() != 0)
        return input_error(where + ": split face count does not match its records");
    if (!values.ok()) return input_error(where + ": split values do not end where the chunk does");
    if (m.decoded_splits_ == m.split_count_) {
        if (m.decoded_faces_ != m.face_count_) return input_error(where + ": face count does not match INFO");
        m.release_decoding_state();
    }
    return ok_status();
}

Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm_bytes(std::span<const uint8_t> bytes,
                                                                     const std::string& source_name,
                                                                     BpmStream::FaceOrder order) {
    BpmStream stream(source_name, order);
    stream.expect_whole_file();
    Status st = stream.feed(bytes);
    if (!st) return st.error();
    st = stream.finish();
    if (!st) return st.error();
    std::vector<std::unique_ptr<ProgressiveMesh>> out;
    for (size_t i = 0; i < stream.structure_count(); ++i) {
        auto m = std::make_unique<ProgressiveMesh>(std::move(stream.structure(i)));
        out.push_back(std::move(m));
    }
    return out;
}

Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm(const std::string& path, BpmStream::FaceOrder order) {
    // Streamed in chunks: a wrong header fails after 16 bytes, not after the whole file.
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) return input_error(path + ": cannot open: " + std::strerror(errno));
    BpmStream stream(path, order);
    stream.expect_whole_file();
    std::vector<uint8_t> chunk(1 << 20);
    size_t n = std::fread(chunk.data(), 1, kFileHeaderSize, file.get());
    while (n > 0) {
        if (Status st = stream.feed({chunk.data(), n}); !st) return st.error();
        n = std::fread(chunk.data(), 1, chunk.size(), file.get());
    }
    if (std::ferror(file.get())) return input_error(path + ": read failed");
    if (Status st = stream.finish(); !st) return st.error();
    std::vector<std::unique_ptr<ProgressiveMesh>> out;
    for (size_t i = 0; i < stream.structure_count(); ++i)
        out.push_back(std::make_unique<ProgressiveMesh>(std::move(stream.structure(i))));
    return out;
}

}  // namespace body::pm
