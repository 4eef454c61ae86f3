// The ProgressiveMesh runtime: levels, refine/coarsen, dirty ranges, released
// arrays, morph sources (the reader fills it: bpm_reader.cpp). After H. Hoppe,
// "Progressive meshes", SIGGRAPH 1996.
#include "shared/pm/progressive_mesh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

#include "shared/pm/bpm_container.h"
#include "shared/pm/draw_order.h"
#include "shared/pm/index_code.h"
#include "shared/pm/split_codec.h"

namespace body::pm {

float ProgressiveMesh::quantization_bound() const {
    Vec3f step = (bbox_max_ - bbox_min_) / float(kMaxCode16);
    // Half a step per axis, plus float rounding of the dequantized value.
    float ulp = 4e-7f * std::max({std::fabs(bbox_min_.x), std::fabs(bbox_min_.y), std::fabs(bbox_min_.z),
                                  std::fabs(bbox_max_.x), std::fabs(bbox_max_.y), std::fabs(bbox_max_.z)});
    return 0.5f * glm::length(step) + 2.0f * ulp;
}

float ProgressiveMesh::position_bound() const {
    return quantization_bound() + float(0.5 * std::sqrt(3.0) * kCoarseFraction * double(error_at(level())));
}

void ProgressiveMesh::positions(size_t begin, std::span<Vec3f> out) const {
    for (size_t i = 0; i < out.size(); ++i) out[i] = dequantize(&positions_[(begin + i) * 3]);
}

Vec3f ProgressiveMesh::normal(size_t v) const {
    if (!has_normals_) return Vec3f(0.0f, 0.0f, 1.0f);
    float n[3];
    oct_decode8(&normals_[v * 2], n);
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
    return drawable_below(level);
}

size_t ProgressiveMesh::drawable_below(size_t level) const {
    if (level >= ordered_level()) return level;
    const auto end = batch_levels_.begin() + ptrdiff_t(ordered_batches_);
    const auto it = std::upper_bound(batch_levels_.begin(), end, uint32_t(level));
    return it == batch_levels_.begin() ? 0 : *(it - 1);
}

size_t ProgressiveMesh::drawable_above(size_t level) const {
    if (level == 0 || level >= ordered_level()) return level;
    const auto end = batch_levels_.begin() + ptrdiff_t(ordered_batches_);
    return *std::lower_bound(batch_levels_.begin(), end, uint32_t(level));
}

// Called by the reader when split `level` - 1, the last of batch
// ordered_batches_, is recorded: sorts the batch's faces into cache order on
// the connectivity at `level` (the replay's), numbers the batch's vertices in
// the order those faces first use them, and renumbers what points at either.
void ProgressiveMesh::order_batch(size_t level) {
    const size_t lo = ordered_level();
    // A level inside the batch would stop being a prefix: moved to its end first.
    // (The reader counts the chunk's splits as decoded at its end: counted here for the move.)
    if (level_ > lo && level_ < level) {
        const size_t decoded = decoded_splits_;
        decoded_splits_ = level;
        refine_to(level);
        decoded_splits_ = decoded;
    }
    const size_t f0 = triangles_at(lo), f1 = decoded_faces_, n = f1 - f0;
    ++ordered_batches_;
    if (n == 0) return;
    // The batch's faces at `level` are the replay's (the file's numbers; its own
    // vertices still have their file numbers in draw order too): their order,
    // and the batch's vertices in the order the ordered faces first use them.
    // Scratch reused batch to batch, sized without zeroing (each entry is written before it is read).
    const auto sized = [](UninitVector<uint32_t>& v, size_t size) -> UninitVector<uint32_t>& {
        v.clear();
        v.resize(size);
        return v;
    };
    const uint32_t* const replayed = replay_.indices() + f0 * 3;
    auto& order = sized(order_scratch_.order, n);
    cache_order(replayed, n, qpos_.data(), order.data(), order_scratch_);
    const uint32_t v0 = uint32_t(base_vertices_ + lo), nv = uint32_t(level - lo);
    auto& number = sized(order_scratch_.number, std::max<uint32_t>(nv, 1));
    first_use_order(replayed, order.data(), n, v0, nv, number.data());
    auto& faces = sized(order_scratch_.faces, n * 3);
    const auto renumber = [&](uint32_t v) {  // without a branch: older vertices are interleaved unpredictably
        const uint32_t k = v - v0, inside = 0u - uint32_t(k < nv), renumbered = number[k & inside];
        return v ^ ((v ^ renumbered) & inside);
    };
    // The faces' entries at level_ (scratch: the old entries), moved and renumbered.
    std::copy(indices_.begin() + ptrdiff_t(f0 * 3), indices_.begin() + ptrdiff_t(f1 * 3), faces.begin());
    for (size_t t = 0; t < n; ++t) {
        if (t + kGatherAhead < n) {
            prefetch(&faces[size_t(order[t + kGatherAhead]) * 3]);
            prefetch(&face_slot_[f0 + order[t + kGatherAhead]]);
        }
        const size_t f = order[t];
        for (size_t k = 0; k < 3; ++k) indices_[(f0 + t) * 3 + k] = renumber(faces[f * 3 + k]);
        face_slot_[f0 + f] = uint32_t(f0 + t);
    }
    // The splits' records: children, parents, and their patches, which name the
    // batch's faces (moved) or older ones (which hold, at `level`, the child of
    // the batch's last split patching them: renumbered in indices_ when the
    // current level is past the batch; below it they do not hold the child).
    for (size_t j = lo; j < level; ++j) {
        store_le(&split_children_bytes_[j * parent_bytes_], number[j - lo], parent_bytes_);
        store_le(&split_parents_bytes_[j * parent_bytes_], renumber(split_parent(j)), parent_bytes_);
    }
    const size_t w = corner_bytes_, patches_end = patch_corners_.size() / w;
    for (size_t i = batch_patch_begin_; i < patches_end; ++i) {
        if (i + kGatherAhead < patches_end) prefetch(&face_slot_[patch_corner(i + kGatherAhead) / 3]);
        const uint32_t c = patch_corner(i);
        if (c >= f0 * 3) store_le(&patch_corners_[i * w], face_slot_[c / 3] * 3 + c % 3, w);
    }
    if (level_ >= level) {
        size_t i = batch_patch_begin_;
        for (size_t j = lo; j < level; ++j)
            for (const size_t e = i + patch_count_[j]; i < e; ++i)
                if (const uint32_t c = patch_corner(i); c < f0 * 3) indices_[c] = number[j - lo];
    }
    batch_patch_begin_ = patches_end;
    // The vertex data in the new numbers (the file's numbers map there from now on).
    for (uint32_t k = 0; k < nv; ++k) vertex_slot_[v0 + k] = number[k];
    permute_vertices(v0, {number.data(), nv});
    dirty_vertices_.add(v0, v0 + nv);
    dirty_indices_.add(f0 * 3, f1 * 3);
}

// Vertex v0 + k moves to number[k] (a permutation of [v0, v0 + number.size())).
void ProgressiveMesh::permute_vertices(uint32_t v0, std::span<const uint32_t> number) {
    const size_t nv = number.size();
    // Element by element: a copy_n of 2 or 3 elements is a memmove call a vertex.
    std::vector<uint16_t> codes(positions_.begin() + ptrdiff_t(v0) * 3, positions_.begin() + ptrdiff_t(v0 + nv) * 3);
    for (size_t k = 0; k < nv; ++k) {
        uint16_t* to = &positions_[size_t(number[k]) * 3];
        to[0] = codes[k * 3];
        to[1] = codes[k * 3 + 1];
        to[2] = codes[k * 3 + 2];
    }
    if (!has_normals_) return;
    std::vector<uint8_t> octs(normals_.begin() + ptrdiff_t(v0) * 2, normals_.begin() + ptrdiff_t(v0 + nv) * 2);
    for (size_t k = 0; k < nv; ++k) {
        normals_[size_t(number[k]) * 2] = octs[k * 2];
        normals_[size_t(number[k]) * 2 + 1] = octs[k * 2 + 1];
    }
}

size_t ProgressiveMesh::level_for_error(float error) const {
    // The values are non-increasing: the first level of the first value <= error
    // is the coarsest such level (the decoded levels only).
    auto it = std::partition_point(error_highs_.begin(), error_highs_.end(),
                                   [&](uint16_t e) { return error_value(e) > error; });
    if (it == error_highs_.end()) return decoded_splits_;
    return drawable_above(std::min<size_t>(error_levels_[size_t(it - error_highs_.begin())], decoded_splits_));
}

size_t ProgressiveMesh::refine_to(size_t level) {
    level = drawable_below(std::min(level, decoded_splits_));
    size_t e = patch_at_level_;
    for (size_t j = level_; j < level; ++j) {
        const uint32_t child = split_child(j);
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
    level = drawable_below(level);
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

bool ProgressiveMesh::pack_indices() {
    if (indices_released_) return indices_packed();
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    const size_t n = indices_.size();
    const size_t bits = index_code_bits(max_vertex_count());
    uint32_t* w = indices_.data();
    const size_t out = pack_index_code(std::span<uint32_t>(w, n), bits);
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
    unpack_index_code(std::span<const uint32_t>(packed_indices_.data(), packed_words_), packed_bits_,
                      out.first(packed_count_));
    UninitVector<uint32_t>().swap(packed_indices_);
    packed_bits_ = packed_count_ = packed_words_ = 0;
    patch_indices(out, 0);  // the levels moved since it was packed
}

bool ProgressiveMesh::release_vertex_data() {
    if (vertices_released_) return true;
    if (decoded_splits_ != split_count_ || !base_ready_) return false;
    UninitVector<uint16_t>().swap(positions_);
    UninitVector<uint8_t>().swap(normals_);
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
            const uint32_t child = split_child(j);
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
    const size_t hi_vc = vertex_count();
    // The sources start at the lowest vertex added since lo or moved by a split
    // since lo (the vertices added since lo are [base + lo, hi_vc) at a drawable
    // lo, in any order inside a batch).
    size_t begin = hi_vc;
    for (size_t j = lo; j < level_; ++j) {
        begin = std::min<size_t>(begin, split_child(j));
        if (moves_parent(j)) begin = std::min<size_t>(begin, split_parent(j));
    }
    // Codes first, held exactly as floats (< 2^16): every vertex where it is;
    // the moves since lo undone (each split's move is an XOR, so the order does
    // not matter); then, in split order (a parent before its children), each
    // vertex added since lo takes its parent's source, which overwrites any
    // move undone on it.
    out.resize(hi_vc - begin);
    auto code = [&](size_t v) {
        const uint16_t* q = &positions_[v * 3];
        return Vec3f(q[0], q[1], q[2]);
    };
    for (size_t v = begin; v < hi_vc; ++v) out[v - begin] = code(v);
    for (size_t j = lo; j < level_; ++j) {
        if (!moves_parent(j)) continue;
        Vec3f& q = out[split_parent(j) - begin];
        const uint16_t* move = parent_move(j);
        for (int k = 0; k < 3; ++k) q[k] = float(uint16_t(q[k]) ^ move[k]);
    }
    for (size_t j = lo; j < level_; ++j) {
        const uint32_t p = split_parent(j);
        out[split_child(j) - begin] = p >= begin ? out[p - begin] : code(p);
    }
    for (Vec3f& q : out) {
        const uint16_t c[3] = {uint16_t(q.x), uint16_t(q.y), uint16_t(q.z)};
        q = dequantize(c);
    }
    return begin;
}

void ProgressiveMesh::free_replay_and_codes() {
    // Swapped out, not `= {}` (that empties a vector but keeps its storage).
    replay_ = SplitReplay{};
    order_scratch_ = {};
    UninitVector<uint16_t>().swap(qpos_);
    UninitVector<uint8_t>().swap(qoct_);
}

void ProgressiveMesh::release_decoding_state() {
    free_replay_and_codes();
    UninitVector<uint32_t>().swap(face_slot_);
    UninitVector<uint32_t>().swap(vertex_slot_);
    // patch_corners_ grew geometrically while the splits arrived: to its size,
    // now that the replay's larger arrays are gone (the copy adds no peak).
    patch_corners_.shrink_to_fit();
    moves_.resize(move_count_ * 3);  // to the splits that move their parent
    moves_.shrink_to_fit();
    error_levels_.shrink_to_fit();
    error_highs_.shrink_to_fit();
}

}  // namespace body::pm
