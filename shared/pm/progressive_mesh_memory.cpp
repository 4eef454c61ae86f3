// What a ProgressiveMesh holds (contract at heap_bytes() in progressive_mesh.h).
#include <algorithm>

#include "shared/pm/progressive_mesh.h"

namespace body::pm {

namespace {
template <class V>
size_t bytes_of(const V& v) {
    return v.capacity() * sizeof(typename V::value_type);
}
}  // namespace

namespace {
// The next size of an array that must hold `need` of at most `full` entries,
// `have` held: doubles (decoding a file in many sections copies each entry a
// bounded number of times), never past the file's count.
size_t grown(size_t need, size_t have, size_t full) {
    return need <= have ? have : std::min(full, std::max(need, 2 * have));
}
// Resized to exactly `n` (a plain resize past the capacity may overshoot).
template <class V>
void grow_to(V& v, size_t n) {
    if (v.size() >= n) return;
    v.reserve(n);
    v.resize(n);
}
template <class V>
void grow_zeroed(V& v, size_t n) {
    if (v.size() >= n) return;
    v.reserve(n);
    v.resize(n, 0);
}
}  // namespace

void ProgressiveMesh::grow_decoded(size_t splits, size_t faces) {
    const size_t s = grown(splits, grown_splits_, split_count_), f = grown(faces, grown_faces_, face_count_);
    grown_splits_ = s;
    grown_faces_ = f;
    const size_t v = base_vertices_ + s;
    // The renderer's arrays: entries are written as splits decode, only decoded ones are read.
    grow_to(positions_, v * 3);
    if (has_normals_) grow_to(normals_, v * 2);
    grow_to(indices_, f * 3);
    grow_to(split_parents_bytes_, s * parent_bytes_);
    grow_zeroed(face_count_bits_, (s + 31) / 32);
    grow_to(face_sample_, s / 64 + 1);
    // At most one entry per split and per value (non-increasing below 0x7f81):
    // reserved so that decoding a split never allocates.
    error_levels_.reserve(std::min<size_t>(s, 0x7f81));
    error_highs_.reserve(std::min<size_t>(s, 0x7f81));
    grow_zeroed(move_bits_, s / 64 + 1);
    grow_to(move_rank_, s / 64 + 1);
    grow_to(moves_, s * 3);  // at most; shrunk to the moves once complete
    grow_to(patch_count_, s);
    grow_to(qpos_, v * 3);
    grow_to(qoct_, v * 2);
    replay_.grow(v, f);
    if (batched()) {
        grow_to(face_slot_, f);
        grow_to(vertex_slot_, v);
        grow_to(split_children_bytes_, s * parent_bytes_);
    }
}

size_t ProgressiveMesh::heap_bytes() const {
    const size_t scratch = bytes_of(order_scratch_.keys) + bytes_of(order_scratch_.faces) +
                           bytes_of(order_scratch_.order) + bytes_of(order_scratch_.number);
    return sizeof(*this) + name_.capacity() + bytes_of(packed_indices_) + bytes_of(positions_) + bytes_of(normals_) +
           bytes_of(indices_) + bytes_of(split_parents_bytes_) + bytes_of(face_count_bits_) + bytes_of(face_sample_) +
           bytes_of(error_levels_) + bytes_of(error_highs_) + bytes_of(patch_count_) + bytes_of(move_bits_) +
           bytes_of(move_rank_) + bytes_of(moves_) + bytes_of(patch_corners_) + bytes_of(batch_levels_) +
           replay_.heap_bytes() + bytes_of(qpos_) + bytes_of(qoct_) + bytes_of(face_slot_) + bytes_of(vertex_slot_) +
           bytes_of(split_children_bytes_) + scratch;
}

}  // namespace body::pm
