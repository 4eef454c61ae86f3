// The .bpm reader (streaming, section by section) and the ProgressiveMesh
// runtime. Format: shared/pm/FORMAT.md. Progressive meshes after H. Hoppe,
// "Progressive meshes", SIGGRAPH 1996; byte codecs are meshoptimizer's
// (A. Kapoulkine, meshopt_decodeVertexBuffer / meshopt_decodeIndexBuffer).
#include "shared/pm/progressive_mesh.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "shared/atomic_file.h"

namespace body::pm {

// ---------------------------------------------------------------- runtime

float ProgressiveMesh::quantization_bound() const {
    Vec3f step = (bbox_max_ - bbox_min_) / 65535.0f;
    // Half a step per axis, plus float rounding of the dequantized value.
    float ulp = 4e-7f * std::max({std::fabs(bbox_min_.x), std::fabs(bbox_min_.y), std::fabs(bbox_min_.z),
                                  std::fabs(bbox_max_.x), std::fabs(bbox_max_.y), std::fabs(bbox_max_.z)});
    return 0.5f * glm::length(step) + 2.0f * ulp;
}

void ProgressiveMesh::positions(size_t begin, std::span<Vec3f> out) const {
    for (size_t i = 0; i < out.size(); ++i) out[i] = dequantize(&positions_[(begin + i) * 3]);
}

Vec3f ProgressiveMesh::normal(size_t v) const {
    if (!has_normals_) return Vec3f(0.0f, 0.0f, 1.0f);
    float n[3];
    oct_decode8(&qoct_[v * 2], n);
    return Vec3f(n[0], n[1], n[2]);
}

namespace {
// Sum of the 2-bit fields of x.
size_t sum2(uint64_t x) {
    return size_t(std::popcount(x & 0x5555555555555555ull) + 2 * std::popcount(x & 0xaaaaaaaaaaaaaaaaull));
}
uint64_t low_bits(size_t n) { return n >= 64 ? ~uint64_t(0) : (uint64_t(1) << n) - 1; }
}  // namespace

size_t ProgressiveMesh::triangles_at(size_t level) const {
    const size_t b = level / 64, r = level % 64;
    size_t t = face_sample_[b];
    if (r > 0) {
        const uint64_t first = face_count_bits_[2 * b];
        t += r <= 32 ? sum2(first & low_bits(2 * r))
                     : sum2(first) + sum2(face_count_bits_[2 * b + 1] & low_bits(2 * (r - 32)));
    }
    return t;
}

size_t ProgressiveMesh::level_for_triangles(size_t triangles) const {
    if (triangles < base_faces_) return 0;
    // The last sampled level (<= available_level()) with at most that many, then split by split.
    const auto end = face_sample_.begin() + ptrdiff_t(decoded_splits_ / 64 + 1);
    const auto it = std::upper_bound(face_sample_.begin(), end, uint32_t(std::min<size_t>(triangles, UINT32_MAX)));
    size_t level = size_t(it - face_sample_.begin() - 1) * 64, t = face_sample_[level / 64];
    while (level < decoded_splits_ && t + faces_added(level) <= triangles) t += faces_added(level++);
    return level;
}

size_t ProgressiveMesh::level_for_error(float error) const {
    // The values are non-increasing: the first level of the first value <= error
    // is the coarsest such level (the decoded levels only).
    auto it = std::partition_point(error_highs_.begin(), error_highs_.end(),
                                   [&](uint16_t e) { return error_value(e) > error; });
    if (it == error_highs_.end()) return decoded_splits_;
    return std::min<size_t>(error_levels_[size_t(it - error_highs_.begin())], decoded_splits_);
}

size_t ProgressiveMesh::refine_to(size_t level) {
    level = std::min(level, decoded_splits_);
    size_t e = patch_at_level_;
    for (size_t j = level_; j < level; ++j) {
        const uint32_t child = uint32_t(base_vertices_ + j);
        const size_t b = e;
        e = b + patch_count_[j];
        for (size_t i = b; i < e; ++i) {
            const uint32_t c = patch_corner(i);
            if (!indices_released_) indices_[c] = child;
            dirty_indices_.add(c, c + 1);
            if (indices_released_) pending_indices_.add(c, c + 1);
        }
        if (moves_parent(j)) {
            const uint32_t parent = split_parent(j);
            move_parent(j, parent);
            dirty_vertices_.add(parent, parent + 1);
        }
    }
    if (level > level_) {
        level_ = level;
        patch_at_level_ = e;
    }
    return level_;
}

size_t ProgressiveMesh::coarsen_to(size_t level) {
    size_t b = patch_at_level_;
    for (size_t j = level_; j-- > level;) {
        const uint32_t parent = split_parent(j);
        const size_t e = b;
        b = e - patch_count_[j];
        for (size_t i = b; i < e; ++i) {
            const uint32_t c = patch_corner(i);
            if (!indices_released_) indices_[c] = parent;
            dirty_indices_.add(c, c + 1);
            if (indices_released_) pending_indices_.add(c, c + 1);
        }
        if (moves_parent(j)) {
            move_parent(j, parent);
            dirty_vertices_.add(parent, parent + 1);
        }
    }
    if (level < level_) {
        level_ = level;
        patch_at_level_ = b;
    }
    return level_;
}

bool ProgressiveMesh::release_indices() {
    if (indices_released_) return true;
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    UninitVector<uint32_t>().swap(indices_);
    indices_released_ = true;
    index_pages_released_ = 0;
    index_level_ = level_;
    pending_indices_ = DirtyRange{};
    return true;
}

bool ProgressiveMesh::release_indices_upto(size_t end) {
    if (indices_released_) return true;
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    if (end >= indices_.size()) return release_indices();
#if defined(__linux__)
    // Whole pages inside the array only: its first and last page may hold
    // another allocation's bytes.
    const uintptr_t base = reinterpret_cast<uintptr_t>(indices_.data());
    const uintptr_t page = uintptr_t(::sysconf(_SC_PAGESIZE));
    const uintptr_t lo = std::max((base + page - 1) / page * page, base + index_pages_released_);
    const uintptr_t hi = (base + end * sizeof(uint32_t)) / page * page;
    if (hi > lo && ::madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED) == 0)
        index_pages_released_ = hi - base;
#endif
    return true;
}

// The packed index code (pack_indices / fill_indices): each entry as the
// zigzag difference to a reference, corner 0 of a face against corner 0 of the
// face before, corners 1 and 2 against their face's corner 0 (a split's new
// faces share its child and parent, whose numbers are close); a difference
// below 4 takes 1 + 2 bits, any other 1 + packed_bits_ bits. The 1.1M-triangle
// bunny: 14.7 bits an entry instead of 20 for the plain vertex number (38% of
// its entries are small, the rest spread over the whole vertex range).
namespace {
constexpr uint32_t kSmallIndexBits = 2;
// In-place packing needs every entry's code within its own 32 bits.
static_assert(std::bit_width(2 * uint64_t(kMaxVertices - 1)) + 1 <= 32);
uint32_t zigzag(int64_t d) { return d < 0 ? uint32_t(-2 * d - 1) : uint32_t(2 * d); }
int64_t unzigzag(uint32_t z) { return (z & 1) ? -int64_t(z >> 1) - 1 : int64_t(z >> 1); }
}  // namespace

bool ProgressiveMesh::pack_indices() {
    if (indices_released_) return indices_packed();
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    const size_t n = indices_.size();
    // Wide enough for the zigzag of any difference between two vertex numbers.
    const size_t bits = std::max<size_t>(1, size_t(std::bit_width(2 * uint64_t(max_vertex_count() - 1))));
    // In place: entry i takes at most 1 + bits <= 32 bits, so the words written
    // after reading entry i are words <= i.
    uint32_t* w = indices_.data();
    uint64_t acc = 0;
    size_t held = 0, out = 0;
    uint32_t prev_first = 0, first = 0;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t v = w[i];
        uint32_t reference = first;
        if (i % 3 == 0) {
            reference = prev_first;
            prev_first = first = v;
        }
        const uint32_t z = zigzag(int64_t(v) - int64_t(reference));
        if (z < (1u << kSmallIndexBits)) {
            acc |= uint64_t(z) << (held + 1);  // flag 0
            held += 1 + kSmallIndexBits;
        } else {
            acc |= (uint64_t(1) | uint64_t(z) << 1) << held;
            held += 1 + bits;
        }
        if (held >= 32) {
            w[out++] = uint32_t(acc);
            acc >>= 32;
            held -= 32;
        }
    }
    if (held > 0) w[out++] = uint32_t(acc);
#if defined(__linux__)
    const uintptr_t base = reinterpret_cast<uintptr_t>(w), page = uintptr_t(::sysconf(_SC_PAGESIZE));
    const uintptr_t lo = (base + out * 4 + page - 1) / page * page, hi = (base + n * 4) / page * page;
    if (hi > lo) ::madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_DONTNEED);
#endif
    packed_indices_.swap(indices_);
    packed_bits_ = bits;
    packed_count_ = n;
    packed_words_ = out;
    indices_released_ = true;
    index_level_ = level_;
    pending_indices_ = DirtyRange{};
    return true;
}

void ProgressiveMesh::fill_indices(std::span<uint32_t> out) {
    if (!indices_packed() || out.size() < packed_count_) return;
    const uint32_t* w = packed_indices_.data();
    size_t word = 0;
    uint64_t acc = 0;
    size_t held = 0;
    auto take = [&](size_t count) {  // the next `count` (<= 32) bits of the stream
        if (held < count) {
            acc |= uint64_t(word < packed_words_ ? w[word] : 0) << held;
            ++word;
            held += 32;
        }
        const uint32_t v = uint32_t(acc & ((uint64_t(1) << count) - 1));
        acc >>= count;
        held -= count;
        return v;
    };
    uint32_t prev_first = 0, first = 0;
    for (size_t i = 0; i < packed_count_; ++i) {
        const uint32_t z = take(1) ? take(packed_bits_) : take(kSmallIndexBits);
        const uint32_t reference = i % 3 == 0 ? prev_first : first;
        const uint32_t v = uint32_t(int64_t(reference) + unzigzag(z));
        if (i % 3 == 0) prev_first = first = v;
        out[i] = v;
    }
    UninitVector<uint32_t>().swap(packed_indices_);
    packed_bits_ = packed_count_ = packed_words_ = 0;
    patch_indices(out, 0);  // the levels moved since it was packed
}

bool ProgressiveMesh::release_vertex_data() {
    if (vertices_released_) return true;
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    UninitVector<uint16_t>().swap(positions_);
    UninitVector<uint8_t>().swap(qoct_);
    vertices_released_ = true;
    position_level_ = level_;
    pending_vertices_ = DirtyRange{};
    return true;
}

void ProgressiveMesh::patch_position_codes(std::span<uint16_t> window, size_t first) {
    if (!vertices_released_) return;
    // Each move is an XOR: the splits between the two levels in any order.
    const size_t n = window.size() / 3;
    for (size_t j = std::min(position_level_, level_); j < std::max(position_level_, level_); ++j) {
        const size_t p = split_parent(j);
        if (!moves_parent(j) || p < first || p - first >= n) continue;
        const uint16_t* move = parent_move(j);
        for (size_t k = 0; k < 3; ++k) window[(p - first) * 3 + k] ^= move[k];
    }
    position_level_ = level_;
    pending_vertices_ = DirtyRange{};
}

void ProgressiveMesh::patch_indices(std::span<uint32_t> window, size_t first) {
    if (!indices_released_) return;
    auto put = [&](size_t c, uint32_t v) {
        if (c >= first && c - first < window.size()) window[c - first] = v;
    };
    // Where split min(index_level_, level_)'s patches start: patch_at_level_ is
    // split level_'s, the splits in between are counted off.
    size_t at = patch_at_level_;
    if (index_level_ < level_) {
        for (size_t j = index_level_; j < level_; ++j) at -= patch_count_[j];
        for (size_t j = index_level_; j < level_; ++j) {
            const uint32_t child = uint32_t(base_vertices_ + j);
            for (const size_t e = at + patch_count_[j]; at < e; ++at) put(patch_corner(at), child);
        }
    } else if (index_level_ > level_) {
        for (size_t j = level_; j < index_level_; ++j) at += patch_count_[j];
        for (size_t j = index_level_; j-- > level_;) {
            const uint32_t parent = split_parent(j);
            for (const size_t b = at - patch_count_[j]; at > b;) put(patch_corner(--at), parent);
        }
    }
    index_level_ = level_;
    pending_indices_ = DirtyRange{};
}

size_t ProgressiveMesh::morph_sources(size_t lo, std::vector<Vec3f>& out) const {
    lo = std::min(lo, level_);
    const size_t lo_vc = base_vertices_ + lo, hi_vc = vertex_count();
    // The lowest older vertex that a split since lo moves: the sources start there.
    size_t begin = lo_vc;
    for (size_t j = lo; j < level_; ++j) {
        const uint32_t p = split_parent(j);
        if (p < begin && moves_parent(j)) begin = p;
    }
    // Codes first, held exactly as floats (< 2^16): the older vertices where they
    // are, taken back to lo by undoing the moves since lo (each split's move is
    // an XOR, so the order does not matter); then each vertex added since lo
    // takes its parent's source (set before: p < c).
    out.resize(hi_vc - begin);
    auto code = [&](size_t v) {
        const uint16_t* q = &positions_[v * 3];
        return Vec3f(q[0], q[1], q[2]);
    };
    for (size_t v = begin; v < lo_vc; ++v) out[v - begin] = code(v);
    for (size_t j = lo; j < level_; ++j) {
        const uint32_t p = split_parent(j);
        if (p < begin || p >= lo_vc || !moves_parent(j)) continue;
        Vec3f& q = out[p - begin];
        const uint16_t* move = parent_move(j);
        for (int k = 0; k < 3; ++k) q[k] = float(uint16_t(q[k]) ^ move[k]);
    }
    for (size_t j = lo; j < level_; ++j) {
        const size_t c = base_vertices_ + j;
        const uint32_t p = split_parent(j);
        out[c - begin] = p >= begin ? out[p - begin] : code(p);
    }
    for (Vec3f& q : out) {
        const uint16_t c[3] = {uint16_t(q.x), uint16_t(q.y), uint16_t(q.z)};
        q = dequantize(c);
    }
    return begin;
}

void ProgressiveMesh::release_decoding_state() {
    // Swapped out, not `= {}` (that empties a vector but keeps its storage).
    replay_ = SplitReplay{};
    UninitVector<uint16_t>().swap(qpos_);
    if (!has_normals_) UninitVector<uint8_t>().swap(qoct_);  // with normals: kept as them
    // patch_corners_ grew geometrically while the splits arrived: to its size,
    // now that the replay's larger arrays are gone (the copy adds no peak).
    patch_corners_.shrink_to_fit();
    moves_.resize(move_count_ * 3);  // to the splits that move their parent
    moves_.shrink_to_fit();
    error_levels_.shrink_to_fit();
    error_highs_.shrink_to_fit();
}

// ---------------------------------------------------------------- reader

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
