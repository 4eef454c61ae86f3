#pragma once
// The connectivity replay of vertex splits, shared by the `.bpm` writer and
// reader (see the class comment).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shared/pm/large_array.h"

namespace body::pm {

// The connectivity replay shared by writer and reader. It tracks, for the most
// refined level decoded so far, which corners (face * 3 + k) reference each
// vertex, so that a split's index patches can be sent as a bit mask over its
// parent's corners (sorted ascending) instead of explicit corner numbers.
//
// Storage is laid out for the reader's speed (it is memory-latency bound): each
// vertex's corners sit contiguously and ascending in one pool region (a vertex
// that outgrows its region moves to a twice larger one at the end of the pool),
// so listing them is one or two cache lines instead of a linked-list walk, and
// prefetch() can pull a split's data in ahead of use. The pointer forms below
// allocate nothing (the pool is reserved by reset() for the common case).
class SplitReplay {
public:
    void reset(size_t vertex_capacity, size_t face_capacity);
    // The reader's form: reset(vertex_capacity, 0) without the room, then grow()
    // as sections arrive: storage follows the vertices and faces decoded, not
    // the file's full detail (a structure parked half-way holds half).
    void clear(size_t vertex_capacity);
    // Room for the corners of `vertices` vertices and `faces` faces (never
    // shrinks; faces must stay within what reset/clear's owner announced).
    void grow(size_t vertices, size_t faces);
    // The descriptors of the first `vertices` vertices (<= the capacity) at
    // once, for a reader that will decode them all (a whole file): growing
    // them as vertices arrive copies and faults in each size in turn.
    void hold_vertices(size_t vertices);
    // Appends faces [first_face, first_face + count) with the given indices; their
    // corners must be above every corner added before (faces arrive in order).
    void add_faces(size_t first_face, std::span<const uint32_t> indices);
    // The corners of `v`, ascending, into `out` (cleared first).
    void corners_of(uint32_t v, std::vector<uint32_t>& out) const;
    // The same into out[0 ..): returns the count, or SIZE_MAX (nothing usable)
    // when `v` has more than `capacity` corners.
    size_t corners_of(uint32_t v, uint32_t* out, size_t capacity) const;
    // Moves the corners selected by `mask` (bit i = i-th of corners_of(parent))
    // to `child` (a vertex without corners yet), writing them to `moved`. False if
    // the mask names a missing corner.
    bool apply_mask(uint32_t parent, uint32_t child, uint64_t mask, std::vector<uint32_t>& scratch,
                    std::vector<uint32_t>& moved);
    // The same given the parent's corners exactly as corners_of returned them
    // (count <= 64) and `moving` == popcount(mask) (the decoder knows it: a
    // library call per split on baseline x86-64): the moved corners, ascending,
    // go to moved[0 .. moving).
    bool apply_mask(uint32_t parent, uint32_t child, uint64_t mask, size_t moving, const uint32_t* corners,
                    size_t count, uint32_t* moved);
    // The neighbours of `v` (vertices sharing a face with it), ascending, into `out`.
    void ring_of(uint32_t v, std::vector<uint32_t>& out) const;
    // The same from v's corners (as corners_of returned them) into out[0 .. 2 * count);
    // returns the number of distinct neighbours.
    size_t ring_of(const uint32_t* corners, size_t count, uint32_t* out) const;
    // The faces around a vertex as one closed fan, counter-clockwise seen from
    // outside, from its corners (as corners_of returned them, count <= 64): fan
    // face t is corners[at[t]] = (v, ring[t], ring[t + 1 mod k]), t = 0 at corners[0].
    // Returns k = count, or 0 when the faces are not one closed manifold fan (a
    // boundary or non-manifold vertex).
    size_t ordered_fan(const uint32_t* corners, size_t count, uint32_t* ring, uint8_t* at) const;
    uint32_t index(size_t corner) const { return indices_[corner]; }
    // Every corner's vertex at the replayed level (index(c) for c < 3 * the faces added).
    const uint32_t* indices() const { return indices_.data(); }
    // Neighbour j of a vertex given its corners (as corners_of returned them): the
    // vertex after (j even) or before (j odd) corner j / 2 in its face; j < 2 * count.
    uint32_t neighbour(const uint32_t* corners, size_t j) const {
        const uint32_t c = corners[j / 2], f = c - c % 3;
        return indices_[f + (c - f + 1 + uint32_t(j % 2)) % 3];
    }
    // Cache hints for a split of parent `v` a few splits ahead: stage 0 its
    // region's descriptor, 1 the region, 2 the faces of its corners and, given
    // `per_face` (one entry a face), their entries there, 3 its neighbours'
    // descriptors and, given `qpos` (3 per vertex) and `per_vertex` (one entry a
    // vertex), their entries there (stages in this order, a few splits apart).
    // No effect on results; `v` must be a valid vertex.
    void prefetch(uint32_t v, int stage, const uint16_t* qpos = nullptr, const uint32_t* per_vertex = nullptr,
                  const uint32_t* per_face = nullptr) const;
    // Vertices given room for corners so far (those that arrived, and some
    // room): the rest have none and cost nothing.
    size_t vertices_held() const { return regions_.size(); }
    // Bytes of storage held (the arrays' capacities; reserved pool included).
    size_t heap_bytes() const {
        return regions_.capacity() * sizeof(Region) + (pool_.capacity() + indices_.capacity()) * sizeof(uint32_t);
    }

private:
    struct Region {
        uint32_t offset = 0, count = 0, capacity = 0;
    };
    uint32_t* make_room(uint32_t v, size_t count);  // v's region with room for `count` corners
    void grow_regions(uint32_t v);                  // regions_ to cover v (geometrically, up to the capacity)
    Region region(uint32_t v) const { return v < regions_.size() ? regions_[v] : Region{}; }
    UninitVector<Region> regions_;  // per vertex arrived so far (and some room); the rest have no corners
    size_t vertex_capacity_ = 0;
    UninitVector<uint32_t> pool_;     // corners, ascending per region (entries past a region's count unused)
    UninitVector<uint32_t> indices_;  // per corner: the vertex at the replayed level (set by add_faces)
};

}  // namespace body::pm
