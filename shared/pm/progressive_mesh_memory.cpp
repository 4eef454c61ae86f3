// What a ProgressiveMesh holds (contract at heap_bytes() in progressive_mesh.h).
#include "shared/pm/progressive_mesh.h"

namespace body::pm {

namespace {
template <class V>
size_t bytes_of(const V& v) {
    return v.capacity() * sizeof(typename V::value_type);
}
}  // namespace

size_t ProgressiveMesh::heap_bytes() const {
    const CacheOrderScratch& s = order_scratch_;
    const size_t scratch = bytes_of(s.keys) + bytes_of(s.local_of) + bytes_of(s.local) + bytes_of(s.sorted) +
                           bytes_of(s.global) + bytes_of(s.start) + bytes_of(s.by_first) + bytes_of(s.window);
    return sizeof(*this) + name_.capacity() + bytes_of(packed_indices_) + bytes_of(positions_) + bytes_of(indices_) +
           bytes_of(split_parents_bytes_) + bytes_of(face_count_bits_) + bytes_of(face_sample_) +
           bytes_of(error_levels_) + bytes_of(error_highs_) + bytes_of(patch_count_) + bytes_of(move_bits_) +
           bytes_of(move_rank_) + bytes_of(moves_) + bytes_of(patch_corners_) + bytes_of(batch_levels_) +
           replay_.heap_bytes() + bytes_of(qpos_) + bytes_of(qoct_) + bytes_of(face_slot_) + scratch;
}

}  // namespace body::pm
