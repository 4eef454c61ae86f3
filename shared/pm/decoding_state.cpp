// A paused structure's decoding state, dropped and rebuilt (contract at
// park_decoding_state() in progressive_mesh.h). The state is the decoded
// level in the file's numbering: its connectivity (the replay), its position
// codes (qpos_) and normal codes (qoct_). The drawn arrays hold the same level
// in draw order, at the level drawn; the split records lead them to the
// decoded level, and face_slot_ / vertex_slot_ back to the file's numbering.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "shared/pm/progressive_mesh.h"

namespace body::pm {

void ProgressiveMesh::park_decoding_state() {
    if (decoding_state_parked_ || !base_ready_ || decoded_splits_ == split_count_) return;
    free_replay_and_codes();
    decoding_state_parked_ = true;
}

void ProgressiveMesh::unpark_decoding_state() {
    if (!decoding_state_parked_) return;
    decoding_state_parked_ = false;
    const bool in_batches = batched();
    const size_t vertices = base_vertices_ + decoded_splits_, corners = decoded_faces_ * 3;
    // Draw numbers to the file's (a permutation of the decoded vertices).
    std::vector<uint32_t> file_vertex;
    if (in_batches) {
        file_vertex.resize(vertices);
        for (size_t v = 0; v < vertices; ++v) file_vertex[vertex_slot_[v]] = uint32_t(v);
    }
    const auto file_of = [&](uint32_t drawn) { return in_batches ? file_vertex[drawn] : drawn; };

    // The codes at the drawn level in the file's numbering, then the parents'
    // moves of the splits from there to the decoded level.
    const size_t grown_vertices = base_vertices_ + grown_splits_;
    qpos_.reserve(grown_vertices * 3);
    qpos_.resize(grown_vertices * 3);
    qoct_.reserve(grown_vertices * 2);
    qoct_.resize(grown_vertices * 2);
    for (size_t v = 0; v < vertices; ++v) {
        const size_t d = vertex_in_draw_order(uint32_t(v));
        std::copy_n(&positions_[d * 3], 3, &qpos_[v * 3]);
        // Without normals the codes are only ever copied from parent to child: any value does.
        qoct_[v * 2] = has_normals_ ? normals_[d * 2] : 0;
        qoct_[v * 2 + 1] = has_normals_ ? normals_[d * 2 + 1] : 0;
    }
    // The index array at the decoded level, as refine_to would leave it (the drawn one stays).
    std::vector<uint32_t> drawn(indices_.begin(), indices_.begin() + ptrdiff_t(corners));
    size_t e = patch_at_level_;
    for (size_t j = level_; j < decoded_splits_; ++j) {
        const uint32_t child = split_child(j);
        for (const size_t end = e + patch_count_[j]; e < end; ++e) drawn[patch_corner(e)] = child;
        if (moves_parent(j)) {
            const uint16_t* move = parent_move(j);
            const size_t p = file_of(split_parent(j));
            for (size_t k = 0; k < 3; ++k) qpos_[p * 3 + k] ^= move[k];
        }
    }
    // The faces in the file's order and numbering: face f is drawn as face face_slot_[f], corner for corner.
    std::vector<uint32_t> replayed(corners);
    for (size_t f = 0; f < decoded_faces_; ++f) {
        const size_t d = in_batches ? size_t(face_slot_[f]) : f;
        for (size_t k = 0; k < 3; ++k) replayed[f * 3 + k] = file_of(drawn[d * 3 + k]);
    }
    std::vector<uint32_t>().swap(drawn);
    replay_.clear(base_vertices_ + split_count_);
    replay_.grow(grown_vertices, grown_faces_);
    replay_.add_faces(0, replayed);
}

}  // namespace body::pm
