#pragma once
// Progressive meshes at run time: the ProgressiveMesh the kiosk draws, as the
// `.bpm` reader (bpm_reader.h) fills it. Format: shared/pm/FORMAT.md. Background: thesis section 3.3.
//
// A level is "k vertex splits applied on top of the base mesh". At level k the
// mesh is exactly
//   vertices  position(0 .. vertex_count())        (a prefix)
//   triangles indices()[0 .. 3 * triangle_count())  (a prefix, three per triangle,
//                                                    counter-clockwise from outside)
// and moving between levels only rewrites a few entries of indices() (the index
// patches of each split), the position of each split's parent (a collapse with
// optimal placement moved it; a split moves it back, 0 to 1 vertex per split)
// and changes the two counts. So the renderer can size its GL buffers once at
// max_vertex_count()/max_triangle_count(), upload what dirty_vertices()/
// dirty_indices() say after each change, and draw the prefixes.
//
// Units are object space (millimetres for anatomy). Positions are kept as the
// file's 16-bit codes per axis in the structure's bounding box (position_codes(),
// 6 bytes a vertex; the renderer draws them as they are) and dequantized on
// demand (position(), positions()), so they differ from the builder's input by
// at most quantization_bound() (half a step per axis) at the full level, and by
// position_bound() at a coarser one. Normals are kept as the
// file's 8:8 octahedral codes (normal_codes(), 2 bytes a vertex; normal()).
//
// Threading: none inside; one ProgressiveMesh per thread at a time.
// Allocation: every array (those a renderer reads: positions, normals,
// indices; the split records; the decoding state) grows with the splits
// decoded, doubling, up to the file's counts (a structure parked half-way
// holds about half); refine_to/coarsen_to never allocate. Once complete
// (decoding state freed) a structure keeps about 57 bytes a vertex split (60 in the
// batched order: each split's vertex number, split_child), 24 of
// them the index array (which can be released to a renderer: release_indices()).
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"
#include "shared/pm/draw_order.h"
#include "shared/pm/large_array.h"
#include "shared/pm/quantize.h"
#include "shared/pm/split_replay.h"

namespace body::pm {

// Half-open range [begin, end) of array elements; empty when begin >= end.
struct DirtyRange {
    size_t begin = 0, end = 0;
    bool empty() const { return begin >= end; }
    void add(size_t b, size_t e) {
        if (b >= e) return;
        if (empty()) {
            begin = b;
            end = e;
        } else {
            begin = b < begin ? b : begin;
            end = e > end ? e : end;
        }
    }
};

class ProgressiveMesh {
public:
    // --- what the file says about the structure
    const std::string& name() const { return name_; }
    Vec3f color() const { return color_; }
    Vec3f bounds_min() const { return bbox_min_; }
    Vec3f bounds_max() const { return bbox_max_; }
    bool has_normals() const { return has_normals_; }
    // Largest distance between a stored and a dequantized position (object units).
    float quantization_bound() const;
    // Largest distance between a position at the current level and the builder's:
    // the quantization, plus the coarser grid of a position a later split moves
    // (version 6: at most kCoarseFraction of the level's error per axis, halved).
    float position_bound() const;

    // --- levels. Level k = k splits applied; 0 is the base mesh.
    size_t max_level() const { return split_count_; }           // all splits of the complete file
    size_t available_level() const { return decoded_splits_; }  // splits decoded so far (streaming)
    bool base_ready() const { return base_ready_; }             // false until the BASE chunk arrived
    size_t level() const { return level_; }
    size_t base_vertex_count() const { return base_vertices_; }
    size_t base_triangle_count() const { return base_faces_; }
    size_t max_vertex_count() const { return base_vertices_ + split_count_; }
    size_t max_triangle_count() const { return face_count_; }
    size_t vertex_count() const { return base_vertices_ + level_; }
    size_t triangle_count() const { return triangles_at(level_); }
    size_t triangles_at(size_t level) const;  // O(1)
    // Object-space error of level k: an estimate of the symmetric Hausdorff distance
    // to the full mesh; non-increasing in k, 0 at max_level().
    float error_at(size_t level) const { return level < split_count_ ? error_value(error_high(level)) : 0.0f; }

    // Level selection, limited to available_level().
    size_t level_for_triangles(size_t triangles) const;  // the finest level with at most that many (>= 0)
    size_t level_for_error(float error) const;           // the coarsest level whose error <= error
    // Batched draw order (draw_order.h): a level is drawable (an exact prefix)
    // when it is a batch boundary or lies in the batch still arriving; the
    // level selectors above return drawable levels. drawable_below(k): the
    // finest drawable level <= k; drawable_above(k): the coarsest >= k (<= available_level()).
    size_t drawable_below(size_t level) const;
    size_t drawable_above(size_t level) const;
    bool batched() const { return !batch_levels_.empty(); }
    std::span<const uint32_t> batch_levels() const { return batch_levels_; }

    // Moves to a level (clamped to [0, available_level()]); cost proportional to
    // the number of splits crossed and their patches. Both return the new level.
    // With batched draw order (draw_order.h), both move to the boundary level
    // at or below the one asked for when that falls inside a reordered batch.
    size_t refine_to(size_t level);
    size_t coarsen_to(size_t level);
    size_t set_level(size_t level) { return level >= level_ ? refine_to(level) : coarsen_to(level); }

    // Geomorph sources for gliding from level `lo` (<= level()) up to the current
    // level: where each vertex is at level lo (a vertex added since lo: where its
    // ancestor is at lo; a vertex moved since lo: where it was; the rest: where
    // it is). Writes them for the vertices [begin, vertex_count()) to `out`
    // (resized to vertex_count() - begin) and returns `begin`, the lowest vertex
    // whose source differs from its position (<= base_vertex_count() + lo).
    // Cost O(level() - lo) plus the copy; the level is not changed; no other
    // memory than `out` (caller-owned, reused across calls: no allocation once grown).
    size_t morph_sources(size_t lo, std::vector<Vec3f>& out) const;

    // --- arrays, at least the decoded vertices / 3 * the decoded triangles
    // (max_vertex_count() / 3 * max_triangle_count() once complete); entries past
    // the current prefix are valid once decoded but are not part of this level.
    // Three codes per vertex in [bounds_min(), bounds_max()]: axis k of vertex v
    // is dequantize16(code, bounds_min()[k], step) with step = (double(max) -
    // double(min)) / 65535 (quantize.h), what position() returns.
    std::span<const uint16_t> position_codes() const { return positions_; }
    Vec3f position(size_t v) const { return dequantize(&positions_[v * 3]); }
    // Dequantizes the positions of the vertices [begin, begin + out.size()) into
    // `out` (caller-owned; no allocation).
    void positions(size_t begin, std::span<Vec3f> out) const;
    // Two octahedral codes per vertex (oct_decode8 in quantize.h); empty when the
    // file has none.
    std::span<const uint8_t> normal_codes() const {
        return has_normals_ ? std::span<const uint8_t>(normals_) : std::span<const uint8_t>();
    }
    Vec3f normal(size_t v) const;  // unit; (0,0,1) when the file has none
    // The vertex split j (< available_level()) adds, and the vertex it splits off.
    // In refinement order split j adds vertex base_vertex_count() + j; in the
    // batched order (draw_order.h) the vertices a batch adds are renumbered
    // among themselves in the order its faces first use them, so a boundary
    // level's vertices are still the prefix [0, vertex_count()) but a split's
    // vertex is only known to lie in its batch's range.
    uint32_t split_child(size_t j) const {
        return split_children_bytes_.empty() ? uint32_t(base_vertices_ + j)
                                             : load_le(&split_children_bytes_[j * parent_bytes_], parent_bytes_);
    }
    uint32_t split_parent(size_t j) const { return load_le(&split_parents_bytes_[j * parent_bytes_], parent_bytes_); }
    // Empty once release_indices() handed the array to a caller's copy.
    std::span<const uint32_t> indices() const { return indices_; }

    // --- the index array kept by the caller only (a renderer's element buffer
    // is its one full copy).
    // release_indices() frees indices(); false (nothing freed) until every split
    // is decoded (streaming writes new faces there). Afterwards refine_to and
    // coarsen_to keep moving the level, the positions and the dirty ranges but
    // leave the index patches pending, and patch_indices() writes them, from the
    // level the caller's array was last brought to up to the current level, into
    // the caller's elements [first, first + window.size()), which must cover
    // pending_index_range() (entries outside the window are left alone). The
    // array at a level depends on the level only, so several moves between two
    // patch_indices() calls cost one pass over the splits between their ends.
    bool release_indices();
    bool indices_released() const { return indices_released_; }
    // For a caller copying the array away in order: the entries [0, end) are
    // copied, so their memory goes back to the system now (whole pages; the
    // entries read as indeterminate afterwards). Reaching the end releases the
    // array as release_indices() does. Returns false (nothing done) where
    // release_indices() would.
    bool release_indices_upto(size_t end);
    // Released with the array kept packed until the caller has its copy:
    // pack_indices() packs the array of the current level in place (each
    // entry as a recent value or a difference, index_code.h: about 12.4
    // bits an entry on a million-triangle mesh where plain numbers take 20;
    // the pages past the packed size handed back) and counts as released (as
    // release_indices(); false where that would be). fill_indices() writes the
    // whole array at the current level into the caller's `out` (>= 3 *
    // max_triangle_count() entries): the packed array plus the patches of the
    // levels moved since; then the packed array is freed.
    bool pack_indices();
    bool indices_packed() const { return packed_bits_ != 0; }
    void fill_indices(std::span<uint32_t> out);
    // Index entries patch_indices() will write (a superset of the entries whose
    // value changes); empty when nothing is pending.
    DirtyRange pending_index_range() const { return pending_indices_; }
    void patch_indices(std::span<uint32_t> window, size_t first);

    // --- the vertex data kept by the caller only, likewise (a renderer's
    // position and normal buffers: 8 bytes a vertex). release_vertex_data()
    // frees position_codes() and normal_codes() (position(), positions(),
    // normal() and morph_sources() may not be called afterwards); false
    // (nothing freed) until every split is decoded. Normals do not change with
    // the level; the positions' pending changes (the parents' moves) are XORed
    // into the caller's codes of the vertices [first, first + window.size() / 3)
    // by patch_position_codes(), which must cover pending_vertex_range().
    bool release_vertex_data();
    bool vertex_data_released() const { return vertices_released_; }
    DirtyRange pending_vertex_range() const { return pending_vertices_; }
    void patch_position_codes(std::span<uint16_t> window, size_t first);

    // Elements changed since clear_dirty(): vertex data newly decoded, index
    // entries newly decoded or patched by refine/coarsen.
    DirtyRange dirty_vertices() const { return dirty_vertices_; }
    DirtyRange dirty_indices() const { return dirty_indices_; }
    void clear_dirty() { dirty_vertices_ = dirty_indices_ = DirtyRange{}; }

    // Bytes of storage the structure holds now (every array's capacity, the
    // decoding state included; progressive_mesh_memory.cpp): what a caller
    // keeps per structure, for memory budgets and their tests.
    size_t heap_bytes() const;

private:
    friend class BpmStream;
    std::string name_;
    Vec3f color_{0.8f}, bbox_min_{0.0f}, bbox_max_{0.0f};
    bool has_normals_ = false, base_ready_ = false;
    size_t base_vertices_ = 0, base_faces_ = 0, face_count_ = 0, split_count_ = 0, chunk_splits_ = 0;
    size_t decoded_splits_ = 0, decoded_faces_ = 0, level_ = 0;
    // Released indices: the level the caller's array is at, and the entries
    // its pending patches touch.
    bool indices_released_ = false, vertices_released_ = false;
    // pack_indices(): packed_count_ entries as a bit stream of packed_words_
    // words of bits packed_bits_ (the code: index_code.h).
    UninitVector<uint32_t> packed_indices_;
    size_t packed_bits_ = 0, packed_count_ = 0, packed_words_ = 0;
    size_t position_level_ = 0;  // released vertex data: the level of the caller's codes
    DirtyRange pending_vertices_;
    size_t index_level_ = 0, index_pages_released_ = 0;  // bytes of indices_ handed back so far
    DirtyRange pending_indices_;

    // Grown with the decoded splits (grow_decoded), written as they decode:
    // entries past the decoded vertices, faces and splits are indeterminate.
    double step_[3] = {0.0, 0.0, 0.0};  // dequantization step per axis
    UninitVector<uint16_t> positions_;  // 3 per vertex: codes at the current level
    UninitVector<uint8_t> normals_;     // 2 per vertex: octahedral codes (files with normals)
    UninitVector<uint32_t> indices_;
    // Per split: its parent vertex, parent_bytes_ bytes, least significant
    // first (3 when every vertex number fits 24 bits, else 4).
    UninitVector<uint8_t> split_parents_bytes_;
    size_t parent_bytes_ = 4;
    // Batched order: per split the vertex it adds (split_child), parent_bytes_ bytes each.
    UninitVector<uint8_t> split_children_bytes_;
    // Vertex and entry numbers kept in 3 or 4 bytes (`bytes`), least significant first.
    static uint32_t load_le(const uint8_t* p, size_t bytes) {
        const uint32_t v = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16;
        return bytes == 4 ? v | uint32_t(p[3]) << 24 : v;
    }
    static void store_le(uint8_t* p, uint32_t v, size_t bytes) {  // unrolled: several calls a split
        p[0] = uint8_t(v);
        p[1] = uint8_t(v >> 8);
        p[2] = uint8_t(v >> 16);
        if (bytes == 4) p[3] = uint8_t(v >> 24);
    }
    // Per split, 2 bits: the faces it adds (1 to 3), 32 splits a word; per 64
    // splits the triangle count at that level (face_sample_[b]: level 64 b), so
    // triangles_at is a sample plus two popcounts.
    UninitVector<uint64_t> face_count_bits_;
    UninitVector<uint32_t> face_sample_;
    size_t faces_added(size_t j) const { return size_t(face_count_bits_[j / 32] >> (j % 32 * 2)) & 3; }
    // Per split: the error of the level before it, the high half of its float
    // (the file codes errors as steps of 2^16 in the float's bits: exact), kept
    // where it changes only: the levels where a new value starts and the values
    // (non-increasing, so at most 32641 of them; typically a few hundred).
    std::vector<uint32_t> error_levels_;
    std::vector<uint16_t> error_highs_;
    uint16_t error_high(size_t level) const {
        const auto it = std::upper_bound(error_levels_.begin(), error_levels_.end(), uint32_t(level));
        return it == error_levels_.begin() ? uint16_t(0x7f80) : error_highs_[size_t(it - error_levels_.begin()) - 1];
    }
    static float error_value(uint16_t high) {
        const uint32_t bits = uint32_t(high) << 16;
        float e;
        std::memcpy(&e, &bits, 4);
        return e;
    }
    // Per split: how many patch_corners_ entries it patches (<= 64); the splits'
    // entries follow one another, and patch_at_level_ is where split level_'s start.
    UninitVector<uint8_t> patch_count_;
    size_t patch_at_level_ = 0;
    // Per split that moves its parent (a bit each, 64 a word, with the count of
    // such splits before every word: most splits of an optimal-placement file),
    // 3 per axis in moves_: the parent's position code before it XOR
    // after it, so refining and coarsening apply the same XOR and morph_sources
    // undoes the moves since a level. Splits that move nothing store nothing.
    UninitVector<uint64_t> move_bits_;
    UninitVector<uint32_t> move_rank_;
    UninitVector<uint16_t> moves_;
    size_t move_count_ = 0;
    const uint16_t* parent_move(size_t j) const {
        const size_t r =
            move_rank_[j / 64] + size_t(std::popcount(move_bits_[j / 64] & ((uint64_t(1) << (j % 64)) - 1)));
        return &moves_[r * 3];
    }
    // Index entries set to the child on refine and the parent on coarsen,
    // corner_bytes_ bytes each, least significant first (3 when every entry
    // number fits 24 bits: up to 5.59M triangles; else 4).
    UninitVector<uint8_t> patch_corners_;
    size_t corner_bytes_ = 4;
    uint32_t patch_corner(size_t i) const { return load_le(&patch_corners_[i * corner_bytes_], corner_bytes_); }
    DirtyRange dirty_vertices_, dirty_indices_;
    // Batched draw order: the boundaries (empty: refinement order) and how many
    // batches are reordered so far (order_batch, called by the reader as each completes).
    std::vector<uint32_t> batch_levels_;
    size_t ordered_batches_ = 0;
    size_t ordered_level() const { return ordered_batches_ ? batch_levels_[ordered_batches_ - 1] : 0; }
    void order_batch(size_t level);
    void permute_vertices(uint32_t v0, std::span<const uint32_t> number);
    // Decoding state, released when the structure is complete. It numbers
    // vertices and faces as the file does (the replay, qpos_, qoct_); the
    // arrays above in draw order.
    SplitReplay replay_;
    UninitVector<uint16_t>
        qpos_;  // 3 per vertex: positions at the finest decoded level (children are coded against parents)
    UninitVector<uint8_t> qoct_;  // 2 per vertex: octahedral normals
    // Batched order: per face (the replay's and the file's numbering) its place
    // in indices_, and the first patch_corners_ entry of the batch arriving.
    UninitVector<uint32_t> face_slot_;
    size_t batch_patch_begin_ = 0;
    // Batched order: per vertex (the file's numbering) its number in draw order.
    UninitVector<uint32_t> vertex_slot_;
    uint32_t vertex_in_draw_order(uint32_t v) const { return vertex_slot_.empty() ? v : vertex_slot_[v]; }
    CacheOrderScratch order_scratch_;
    void release_decoding_state();
    // The replay, qpos_, qoct_ and the order scratch, storage and all: what a
    // paused structure drops and a complete one no longer needs.
    void free_replay_and_codes();
    // Decoding on demand (decoding_state.cpp): a paused structure drops the
    // replay, qpos_ and qoct_ (park) and rebuilds them before its next split
    // (unpark) from what it keeps: the drawn arrays brought to the decoded
    // level by the split records, mapped to the file's numbering through
    // face_slot_ and vertex_slot_ (kept: they record the batches' cache order,
    // which only the decode computes). Exactly the state a decode without the
    // pause has (each vertex's corners ascending; the pool's layout may differ).
    void park_decoding_state();
    void unpark_decoding_state();
    bool decoding_state_parked_ = false;
    // The split records and decoding state grown to cover `splits` splits and
    // `faces` faces, geometrically and capped at the file's counts
    // (progressive_mesh_memory.cpp); the reader calls it before each section.
    void grow_decoded(size_t splits, size_t faces);
    size_t grown_splits_ = 0, grown_faces_ = 0;
    bool moves_parent(size_t j) const { return (move_bits_[j / 64] >> (j % 64)) & 1; }
    void move_parent(size_t j, uint32_t parent) {
        if (vertices_released_) {
            pending_vertices_.add(parent, parent + 1);
            return;
        }
        const uint16_t* move = parent_move(j);
        for (size_t k = 0; k < 3; ++k) positions_[size_t(parent) * 3 + k] ^= move[k];
    }
    Vec3f dequantize(const uint16_t* q) const {
        return Vec3f(dequantize16(q[0], bbox_min_.x, step_[0]), dequantize16(q[1], bbox_min_.y, step_[1]),
                     dequantize16(q[2], bbox_min_.z, step_[2]));
    }
};

}  // namespace body::pm
