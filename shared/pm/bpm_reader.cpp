// See bpm_reader.h. Progressive meshes after H. Hoppe, "Progressive meshes",
// SIGGRAPH 1996; the BASE section's codecs are meshoptimizer's (A. Kapoulkine,
// meshopt_decodeVertexBuffer / meshopt_decodeIndexBuffer).
#include "shared/pm/bpm_reader.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "shared/atomic_file.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/prediction.h"
#include "shared/pm/split_codec.h"

namespace body::pm {

BpmStream::BpmStream(std::string source_name) : source_(std::move(source_name)) {}

namespace {

std::string where_of(const std::string& source, uint32_t tag, uint32_t structure, size_t offset) {
    return source + ": section " + tag_name(tag) + " of structure " + std::to_string(structure) + " at byte " +
           std::to_string(offset);
}

}  // namespace

Status BpmStream::feed(std::span<const uint8_t> bytes) {
    if (failed_) return input_error(failure_);
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
        if (length > (1u << 30)) return fail(where + ": section length " + std::to_string(length) + " too large");
        const size_t total = kSectionHeaderSize + size_t(length) + kSectionTrailerSize;
        if (pending_.size() - pos < total) break;
        if (crc32({s, kSectionHeaderSize + length}) != get_u32(s + kSectionHeaderSize + length))
            return fail(where + ": checksum mismatch");
        Status st = parse_section(tag, structure, {s + kSectionHeaderSize, length}, offset);
        if (!st) return fail(st.error().message);
        pos += total;
    }
    pending_.erase(pending_.begin(), pending_.begin() + ptrdiff_t(pos));
    consumed_ += pos;
    return ok_status();
}

Status BpmStream::finish() const {
    if (failed_) return input_error(failure_);
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
    return parse_splits(m, payload, where);
}

Status BpmStream::parse_info(std::span<const uint8_t> payload, const std::string& where) {
    ByteReader r(payload);
    auto m = std::make_unique<ProgressiveMesh>();
    uint16_t name_length = 0;
    std::span<const uint8_t> name;
    float f[9];
    uint32_t flags, bv, bf, splits, faces, chunk;
    bool ok = r.u16(name_length) && r.bytes(name_length, name);
    for (float& x : f) ok = ok && r.f32(x);
    ok = ok && r.u32(flags) && r.u32(bv) && r.u32(bf) && r.u32(splits) && r.u32(faces) && r.u32(chunk);
    if (!ok) return input_error(where + ": INFO payload too short");
    for (float x : f)
        if (!std::isfinite(x)) return input_error(where + ": non-finite colour or bounds");
    const uint64_t vertices = uint64_t(bv) + splits;
    if (bv == 0 || bf == 0 || faces < bf || vertices > kMaxVertices || faces > kMaxFaces || chunk == 0 ||
        uint64_t(faces - bf) > 3ull * splits)
        return input_error(where + ": inconsistent counts");
    m->name_.assign(name.begin(), name.end());
    m->color_ = Vec3f(f[0], f[1], f[2]);
    m->bbox_min_ = Vec3f(f[3], f[4], f[5]);
    m->bbox_max_ = Vec3f(f[6], f[7], f[8]);
    m->has_normals_ = flags & 1;
    for (int k = 0; k < 3; ++k) m->step_[k] = quantization_step(m->bbox_min_[k], m->bbox_max_[k]);
    m->base_vertices_ = bv;
    m->base_faces_ = bf;
    m->split_count_ = splits;
    m->face_count_ = faces;
    m->chunk_splits_ = chunk;
    // Full capacity, uninitialised: each entry is written when its section
    // arrives, and only decoded entries are read (no page faults for the rest).
    m->positions_.resize(vertices * 3);
    m->parent_bytes_ = vertices <= (uint64_t(1) << 24) ? 3 : 4;
    m->split_parents_bytes_.resize(size_t(splits) * m->parent_bytes_);
    m->indices_.resize(size_t(faces) * 3);
    m->face_count_bits_.assign((size_t(splits) + 31) / 32, 0);
    m->face_sample_.resize(size_t(splits) / 64 + 1);
    m->face_sample_[0] = bf;
    // At most one entry per split and per value (non-increasing below 0x7f81):
    // reserved so that decoding a split never allocates; shrunk once complete.
    m->error_levels_.reserve(std::min<size_t>(splits, 0x7f81));
    m->error_highs_.reserve(std::min<size_t>(splits, 0x7f81));
    m->move_bits_.assign(size_t(splits) / 64 + 1, 0);
    m->move_rank_.resize(size_t(splits) / 64 + 1);
    m->moves_.resize(size_t(splits) * 3);  // at most; shrunk to the moves once complete
    m->move_count_ = 0;
    m->patch_count_.resize(splits);
    m->patch_corners_.clear();
    m->corner_bytes_ = uint64_t(faces) * 3 <= (uint64_t(1) << 24) ? 3 : 4;
    m->qpos_.resize(vertices * 3);
    m->qoct_.resize(vertices * 2);
    m->replay_.reset(vertices, faces);
    meshes_.push_back(std::move(m));
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
    }
    std::copy(decoded_indices_.begin(), decoded_indices_.end(), m.indices_.begin());
    m.replay_.add_faces(0, decoded_indices_);
    m.decoded_faces_ = m.base_faces_;
    m.base_ready_ = true;
    m.dirty_vertices_.add(0, m.base_vertices_);
    m.dirty_indices_.add(0, m.base_faces_ * 3);
    if (m.split_count_ == 0) m.release_decoding_state();
    return ok_status();
}

Status BpmStream::parse_splits(ProgressiveMesh& m, std::span<const uint8_t> payload, const std::string& where) {
    ByteReader r(payload);
    uint32_t first = 0, count = 0, new_faces = 0, vbytes = 0, tbytes = 0;
    std::span<const uint8_t> vbuf, tbuf;
    if (!r.u32(first) || !r.u32(count) || !r.u32(new_faces) || !r.u32(vbytes) || !r.bytes(vbytes, vbuf) ||
        !r.u32(tbytes) || !r.bytes(tbytes, tbuf) || r.left() != 0)
        return input_error(where + ": SPLT payload sizes do not add up");
    if (first != m.decoded_splits_ || count == 0 || count > m.split_count_ - m.decoded_splits_ ||
        new_faces > m.face_count_ - m.decoded_faces_)
        return input_error(where + ": split range " + std::to_string(first) + "+" + std::to_string(count) +
                           " does not follow split " + std::to_string(m.decoded_splits_));
    SplitDecoder decoder;
    if (!decoder.init(vbuf)) return input_error(where + ": split value tables do not decode");
    SplitDecoder::Cursor values = decoder.begin();
    // The chunk's parents come first (the loop below prefetches their data).
    std::vector<uint32_t>& parents = split_parents_;
    parents.resize(count);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t child = uint32_t(m.base_vertices_ + first + i), delta = values.get(kCtxParentDelta);
        if (delta >= child || values.past_end())
            return input_error(where + ": split " + std::to_string(first + i) + ": parent out of range");
        parents[i] = child - 1 - delta;
    }
    // Everything below runs per split: no allocation (the message is built on failure only).
    // Geometric growth: reserving the exact need per section would copy the whole
    // array at every section (quadratic: 0.5 GB of copying for a 1M-triangle file).
    if (const size_t need = m.patch_corners_.size() + size_t(count) * 4 * m.corner_bytes_;
        need > m.patch_corners_.capacity())
        m.patch_corners_.reserve(std::max(need, 2 * m.patch_corners_.capacity()));
    ByteReader topo(tbuf);
    size_t face_cursor = 0;
    float previous_error = first == 0 ? INFINITY : m.error_at(first - 1);
    uint32_t previous_error_bits;
    std::memcpy(&previous_error_bits, &previous_error, 4);
    const Vec3f lo = m.bbox_min_, hi = m.bbox_max_;
    int32_t axis_weight[3], plane_weight[3];
    {
        const float box_lo[3] = {lo.x, lo.y, lo.z}, box_hi[3] = {hi.x, hi.y, hi.z};
        normal_axis_weights(box_lo, box_hi, axis_weight);
        plane_axis_weights(box_lo, box_hi, plane_weight);
    }
    uint32_t corners[64], moved[64], faces_at[9], ring[64];
    uint8_t fan_at[64];
    // The replay is bound by memory latency (a parent is anywhere in the mesh):
    // pull the data of the splits a few steps ahead into the cache in stages.
    constexpr uint32_t kAhead0 = 32, kAhead1 = 20, kAhead2 = 12, kAhead3 = 6;
    for (uint32_t i = 0; i < count; ++i) {
        if (i + kAhead0 < count) m.replay_.prefetch(parents[i + kAhead0], 0);
        if (i + kAhead1 < count) {
            const uint32_t p = parents[i + kAhead1];
            m.replay_.prefetch(p, 1);
            prefetch(&m.qpos_[size_t(p) * 3]);
            prefetch(&m.qoct_[size_t(p) * 2]);
        }
        if (i + kAhead2 < count) m.replay_.prefetch(parents[i + kAhead2], 2);
        if (i + kAhead3 < count) m.replay_.prefetch(parents[i + kAhead3], 3, m.qpos_.data());
        const size_t j = first + i;
        const uint32_t child = uint32_t(m.base_vertices_ + j), parent = parents[i];
        auto fail = [&](const char* what) { return input_error(where + ": split " + std::to_string(j) + ": " + what); };
        const uint32_t kind = values.get(kCtxKind), form = kind >> 1;
        const bool moves = kind & 1;
        // Errors are non-increasing by construction: each is a step down from the previous.
        const uint32_t error_step = values.get(kCtxErrorStep);
        if (error_step > (previous_error_bits >> 16)) return fail("error not monotonic");
        previous_error_bits -= error_step << 16;
        const size_t corner_count = m.replay_.corners_of(parent, corners, 64);
        if (corner_count == SIZE_MAX) return fail("parent has more than 64 corners");
        uint32_t faces = 0;
        uint64_t mask = 0;
        uint16_t from[3];
        for (int k = 0; k < 3; ++k) from[k] = m.qpos_[size_t(parent) * 3 + k];
        // Predictions (the general form: child at the parent, no scaling).
        FanPrediction pred{{from[0], from[1], from[2]}, {0, 0, 0}, {0, 0, 0}};
        uint32_t fan = 0;
        if (form == kTopoFan) {
            // Manifold split: the fan faces from ring[start] to ring[start + length] move to the child.
            fan = uint32_t(m.replay_.ordered_fan(corners, corner_count, ring, fan_at));
            const uint32_t start = values.get(kCtxFanStart), length = values.get(kCtxFanLength) + 1;
            if (fan == 0 || start >= fan || length >= fan) return fail("fan split of a vertex without such a fan");
            uint32_t at = start;
            for (uint32_t t = 0; t < length; ++t, at = at + 1 == fan ? 0 : at + 1) mask |= uint64_t(1) << fan_at[at];
            faces = 2;
            const uint32_t f[6] = {child, parent, ring[start], child, ring[at], parent};
            std::copy_n(f, 6, faces_at);
            // The plane through the parent: its normal (when the file has normals).
            int64_t plane[3];
            plane_normal(&m.qoct_[size_t(parent) * 2], plane_weight, plane);
            predict_fan(m.qpos_.data(), ring, fan, start, length, from, m.has_normals_ ? plane : nullptr, pred);
        } else if (form == kTopoGeneral) {
            uint64_t head = 0;
            if (!topo.varint(head)) return fail("topology record truncated");
            faces = uint32_t(head & 3);
            mask = head >> 2;
            // New faces name their third vertex as a neighbour over the parent's corners
            // before the split.
            for (uint32_t f = 0; f < faces && f < 3; ++f) {
                uint64_t code = 0;
                if (!topo.varint(code) || (code >> 1) >= 2 * corner_count)
                    return fail("a new face names a missing neighbour");
                const uint32_t third = m.replay_.neighbour(corners, size_t(code >> 1));
                uint32_t* t = faces_at + 3 * f;
                t[0] = child;
                t[1] = (code & 1) ? third : parent;
                t[2] = (code & 1) ? parent : third;
            }
        } else {
            return fail("unknown split kind");
        }
        if (faces == 0 || face_cursor + faces > new_faces) return fail("face count out of range");
        // The child's position and the parent's move (0 to 1 positions), as residuals
        // of their predictions.
        uint16_t q[3], to[3];
        uint32_t order[3] = {0, 1, 2};
        if (pred.axis < 3) {
            plane_axes(pred.axis, order[0], order[1]);
            order[2] = pred.axis;
        }
        for (uint32_t i = 0; i < 2; ++i)
            q[order[i]] =
                unzigzag16(uint16_t(values.get_scaled(kCtxChild0 + i, pred.shift[order[i]])), pred.child[order[i]]);
        if (pred.axis < 3)
            q[order[2]] = unzigzag16(uint16_t(values.get_scaled(kCtxChild0 + 2, pred.axis_shift)),
                                     plane_coordinate(pred, from, q, pred.child_dot, 4));
        else
            q[2] = unzigzag16(uint16_t(values.get_scaled(kCtxChild0 + 2, pred.shift[2])), pred.child[2]);
        for (int k = 0; k < 3; ++k) to[k] = from[k];
        if (moves) {
            for (uint32_t i = 0; i < (pred.axis < 3 ? 2u : 3u); ++i) {
                const uint32_t k = order[i];
                const uint16_t reflected = reflect16(from[k], q[k]);
                const uint16_t predicted = fan != 0 ? midpoint16(reflected, pred.parent_centroid[k]) : reflected;
                to[k] = unzigzag16(uint16_t(values.get_scaled(kCtxParent0 + i, pred.shift[k])), predicted);
            }
            if (pred.axis < 3) {
                const int64_t offset = pred.parent_dot - 4 * plane_dot(pred, from, q);
                to[order[2]] = unzigzag16(uint16_t(values.get_scaled(kCtxParent0 + 2, pred.axis_shift)),
                                          plane_coordinate(pred, from, to, offset, 8));
            }
        }
        uint8_t oct[2] = {m.qoct_[size_t(parent) * 2], m.qoct_[size_t(parent) * 2 + 1]};
        if (m.has_normals_) {
            // Predicted from the child's faces after the split (fan form), else the parent's normal.
            if (fan != 0) predict_normal(pred, from, to, axis_weight, oct);
            for (int k = 0; k < 2; ++k) oct[k] = unzigzag8(uint8_t(values.get(kCtxNormal0 + uint32_t(k))), oct[k]);
        }
        if (values.past_end()) return fail("values truncated");
        // Index patches first (on the level before the split), then the new faces.
        if (!m.replay_.apply_mask(parent, child, mask, corners, corner_count, moved))
            return fail("patch mask names a missing corner");
        const std::span<const uint32_t> fi(faces_at, faces * 3);
        m.replay_.add_faces(m.decoded_faces_, fi);
        std::copy(fi.begin(), fi.end(), m.indices_.begin() + ptrdiff_t(m.decoded_faces_ * 3));
        m.decoded_faces_ += faces;
        face_cursor += faces;
        m.face_count_bits_[j / 32] |= uint64_t(faces) << (j % 32 * 2);
        if ((j + 1) % 64 == 0) m.face_sample_[(j + 1) / 64] = uint32_t(m.decoded_faces_);
        if (const auto high = uint16_t(previous_error_bits >> 16);  // the low half is 0
            m.error_highs_.empty() || high != m.error_highs_.back()) {
            m.error_levels_.push_back(uint32_t(j));
            m.error_highs_.push_back(high);
        }
        {
            const size_t at = m.patch_corners_.size(), w = m.corner_bytes_, n = size_t(std::popcount(mask));
            m.patch_corners_.resize(at + n * w);
            for (size_t i = 0; i < n; ++i) ProgressiveMesh::store_le(&m.patch_corners_[at + i * w], moved[i], w);
        }
        m.patch_count_[j] = uint8_t(std::popcount(mask));
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
        ProgressiveMesh::store_le(&m.split_parents_bytes_[j * m.parent_bytes_], parent, m.parent_bytes_);
    }
    if (count > 0) {
        const size_t first_child = m.base_vertices_ + first;
        m.dirty_vertices_.add(first_child, first_child + count);
        m.dirty_indices_.add((m.decoded_faces_ - face_cursor) * 3, m.decoded_faces_ * 3);
    }
    if (face_cursor != new_faces || topo.left() != 0)
        return input_error(where + ": split face count does not match its records");
    if (!values.ok()) return input_error(where + ": split values do not end where the chunk does");
    m.decoded_splits_ += count;
    if (m.decoded_splits_ == m.split_count_) {
        if (m.decoded_faces_ != m.face_count_) return input_error(where + ": face count does not match INFO");
        m.release_decoding_state();
    }
    return ok_status();
}

Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm_bytes(std::span<const uint8_t> bytes,
                                                                     const std::string& source_name) {
    BpmStream stream(source_name);
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

Result<std::vector<std::unique_ptr<ProgressiveMesh>>> read_bpm(const std::string& path) {
    auto data = read_file(path);
    if (!data) return data.error();
    return read_bpm_bytes({reinterpret_cast<const uint8_t*>(data->data()), data->size()}, path);
}

}  // namespace body::pm
