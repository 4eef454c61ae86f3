#pragma once
// Vertex-cache order of a triangle list in place, in bounded memory: the
// triangles sorted along a Morton curve of their first corner's cell (an
// in-place bucket sort), then runs of about kOrderWindowFaces consecutive
// triangles each through pm::cache_order_window's in-place form (shared with
// the decoder's batch order, shared/pm/cache_window.h). The scratch is that of one window plus one
// entry a vertex, not meshoptimizer's whole-mesh tables and a second copy
// (about 3x the index bytes for a 1.1M-triangle level; bench/RESULTS.md).
// Used by level_order.h on the mapped element buffer itself.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shared/pm/cache_window.h"

namespace body::render {

// Triangles per meshoptimizer window (whole cells: may pass it). 8K rather
// than 32K: a quarter of the in-place order's scratch (-1.4 MiB at 1.1M
// triangles) for about 2 % more vertex-cache misses (bench/RESULTS.md).
inline constexpr size_t kOrderWindowFaces = 8192;
// Cells of vertex_cells: 32 per axis, a 15-bit Morton code.
inline constexpr uint32_t kOrderCellBits = 15;

// The Morton cell (kOrderCellBits bits, 5 per axis) of the point at `t`
// (each axis in [0, 1] within the model's box; clamped).
uint16_t order_cell(float tx, float ty, float tz);

// Orders the triangles of `indices` (3 per triangle, each < cells.size();
// cells[v] = order_cell of vertex v) for the vertex cache, in place, each
// triangle's corners as they were. `cancel` (may be null) is polled between
// buckets and windows. Returns false when the input is bad (not a whole
// number of triangles, an index past the cells: `indices` untouched) or when
// cancelled (`indices` then holds the same triangles in some order).
bool order_in_windows(std::span<uint32_t> indices, std::span<const uint16_t> cells,
                      const std::atomic<bool>* cancel = nullptr, size_t window_faces = kOrderWindowFaces);

// A permutation of n triangle positions packed at bit_width(n - 1) bits an
// entry (21 for 1.1M triangles, 2.6 bytes a triangle where uint32_t takes 4):
// the in-place order's record of where each triangle came from, which stays
// held while the level is drawn.
class PackedPermutation {
public:
    void identity(size_t n);  // entry i = i
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    uint32_t operator[](size_t i) const {
        const size_t bit = i * bits_, w = bit >> 6, shift = bit & 63;
        uint64_t v = words_[w] >> shift;
        if (shift + bits_ > 64) v |= words_[w + 1] << (64 - shift);
        return uint32_t(v & mask_);
    }
    void set(size_t i, uint32_t value) {
        const size_t bit = i * bits_, w = bit >> 6, shift = bit & 63;
        words_[w] = (words_[w] & ~(mask_ << shift)) | (uint64_t{value} << shift);
        if (shift + bits_ > 64) {
            const unsigned high = unsigned(64 - shift);
            words_[w + 1] = (words_[w + 1] & ~(mask_ >> high)) | (uint64_t{value} >> high);
        }
    }
    void swap(size_t i, size_t j) {
        const uint32_t a = (*this)[i];
        set(i, (*this)[j]);
        set(j, a);
    }
    size_t bytes() const { return words_.capacity() * sizeof(uint64_t); }  // held
    void clear();                                                          // empty, memory freed

private:
    std::vector<uint64_t> words_;
    size_t size_ = 0;
    unsigned bits_ = 0;
    uint64_t mask_ = 0;
};

// The same order, resumable, for an element buffer that may be mapped only
// between frames (the one being drawn, kiosk/render/level_order.h): the bucket
// sort and the windows advance a slice at a time on the triangles in place,
// and every move is mirrored in `perm` (perm[i]: the position the triangle now
// at i had when the order began), so that between slices the buffer holds the
// same triangles and restore_order() can put them back. The final order is
// order_in_windows()'s. Memory besides perm (PackedPermutation): the cells
// (2 a vertex), the bucket bounds and one window's scratch, until done.
struct SlicedOrder {
    std::vector<uint16_t> cells;  // order_cell of each vertex (freed once sorted)
    size_t vertex_count = 0;
    PackedPermutation perm;             // one entry a triangle of the level
    std::vector<uint32_t> start, next;  // bucket bounds, and each bucket's next unplaced triangle
    size_t bucket = 0;                  // the bucket being filled; == its count: windows
    size_t window_cell = 1, window_begin = 0;
    pm::CacheWindowScratch scratch;
    std::vector<uint32_t> faces, moved;  // one window's order, and what it moves
    std::vector<uint32_t> corners;       // one window's corners by vertex (its own numbering)
    std::vector<uint64_t> firsts;
    bool begun = false, finished = false;
    bool done() const { return finished; }
};

// Starts ordering `indices` (3 per triangle, each < cells.size()): counts the
// buckets, perm the identity. False (nothing started, `s` cleared) when the
// input is bad as order_in_windows() would refuse it.
bool begin_sliced_order(SlicedOrder& s, std::span<const uint32_t> indices, std::vector<uint16_t> cells);
// Advances by about `budget` triangle moves (at least one bucket step or one
// window); `indices` as given to begin. Returns done(); once done the
// working memory is freed and only perm is kept.
bool step_sliced_order(SlicedOrder& s, std::span<uint32_t> indices, size_t budget);
// Puts the triangles of `indices` (ordered partly or wholly by a SlicedOrder
// whose perm this is) back where they stood, in place, and empties perm.
void restore_order(std::span<uint32_t> indices, PackedPermutation& perm);

}  // namespace body::render
