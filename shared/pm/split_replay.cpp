// See split_replay.h.
#include "shared/pm/split_replay.h"

#include <algorithm>
#include <bit>
#include <cstdint>

namespace body::pm {

namespace {
constexpr uint32_t kMinRegion = 8;  // corners: a typical vertex (valence 6) fits with room to grow
// The corner after and before corner k (0 .. 2) in its face, by table: a
// comparison there compiled to a branch that mispredicted about once a split.
constexpr uint32_t kNextCorner[3] = {1, 2, 0}, kPreviousCorner[3] = {2, 0, 1};
}  // namespace

void SplitReplay::reset(size_t vertex_capacity, size_t face_capacity) {
    UninitVector<Region>().swap(regions_);
    vertex_capacity_ = vertex_capacity;
    pool_.clear();  // the writer's next structure reuses the storage
    indices_.clear();
    grow(vertex_capacity, face_capacity);
}

void SplitReplay::clear(size_t vertex_capacity) {
    // Regions grow with the vertices that arrive (grow_regions): a file parked
    // at its base mesh holds its base vertices' only, not its full detail's.
    UninitVector<Region>().swap(regions_);
    vertex_capacity_ = vertex_capacity;
    UninitVector<uint32_t>().swap(pool_);
    UninitVector<uint32_t>().swap(indices_);
}

void SplitReplay::grow(size_t vertices, size_t faces) {
    // Every corner once plus the slack of each region; address space only until used.
    pool_.reserve(faces * 3 + vertices * (kMinRegion + 2));
    if (indices_.size() < faces * 3) {
        indices_.reserve(faces * 3);  // exactly: the caller grows its requests geometrically
        indices_.resize(faces * 3);   // written by add_faces before anything reads them
    }
}

void SplitReplay::hold_vertices(size_t vertices) {
    if (const size_t n = std::min(vertices, vertex_capacity_); regions_.size() < n) {
        regions_.reserve(n);
        regions_.resize(n);  // value-initialised: no corners
    }
}

void SplitReplay::grow_regions(uint32_t v) {
    const size_t n = std::min(std::max<size_t>({size_t(v) + 1, 2 * regions_.size(), 64}), vertex_capacity_);
    regions_.resize(std::max<size_t>(n, size_t(v) + 1));  // value-initialised: no corners
}

uint32_t* SplitReplay::make_room(uint32_t v, size_t count) {
    if (v >= regions_.size()) grow_regions(v);
    Region& r = regions_[v];
    if (count > r.capacity) {
        const size_t capacity = std::max<size_t>({kMinRegion, 2 * size_t(r.capacity), count});
        const size_t offset = pool_.size();
        pool_.resize(offset + capacity);
        std::copy_n(pool_.begin() + r.offset, r.count, pool_.begin() + ptrdiff_t(offset));
        r.offset = uint32_t(offset);
        r.capacity = uint32_t(capacity);
    }
    return pool_.data() + r.offset;
}

void SplitReplay::add_faces(size_t first_face, std::span<const uint32_t> indices) {
    for (size_t i = 0; i < indices.size(); ++i) {
        const uint32_t c = uint32_t(first_face * 3 + i), v = indices[i];
        indices_[c] = v;
        const uint32_t n = region(v).count;
        make_room(v, n + 1)[n] = c;  // the highest corner so far: stays ascending
        regions_[v].count = n + 1;
    }
}

size_t SplitReplay::corners_of(uint32_t v, uint32_t* out, size_t capacity) const {
    const Region r = region(v);
    if (r.count > capacity) return SIZE_MAX;
    std::copy_n(pool_.data() + r.offset, r.count, out);
    return r.count;
}

void SplitReplay::corners_of(uint32_t v, std::vector<uint32_t>& out) const {
    const Region r = region(v);
    out.assign(pool_.data() + r.offset, pool_.data() + r.offset + r.count);
}

size_t SplitReplay::ring_of(const uint32_t* corners, size_t count, uint32_t* out) const {
    // Insertion into a sorted run: a ring has a handful of entries.
    size_t n = 0;
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i], f = c / 3 * 3;
        for (uint32_t k = 0; k < 3; ++k) {
            if (f + k == c) continue;
            const uint32_t x = indices_[f + k];
            size_t at = n;
            while (at > 0 && out[at - 1] > x) --at;
            if (at > 0 && out[at - 1] == x) continue;
            for (size_t m = n; m > at; --m) out[m] = out[m - 1];
            out[at] = x;
            ++n;
        }
    }
    return n;
}

void SplitReplay::ring_of(uint32_t v, std::vector<uint32_t>& out) const {
    std::vector<uint32_t> corners;
    corners_of(v, corners);
    out.resize(2 * corners.size());
    out.resize(ring_of(corners.data(), corners.size(), out.data()));
}

size_t SplitReplay::ordered_fan(const uint32_t* corners, size_t count, uint32_t* ring, uint8_t* at) const {
    if (count < 3 || count > 64) return 0;
    // Faces by the vertex after v in them: a direct-mapped table on its low bits
    // (when two share a slot, a scan instead).
    constexpr uint32_t kSlots = 256;
    uint8_t slot_face[kSlots];
    uint32_t after[64], before[64];  // the vertices after and before v in each face
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i], f = c / 3 * 3, k = c - f;
        after[i] = indices_[f + kNextCorner[k]];
        before[i] = indices_[f + kPreviousCorner[k]];
        slot_face[after[i] % kSlots] = 0xff;
        slot_face[before[i] % kSlots] = 0xff;
    }
    bool hashed = true;
    for (size_t i = 0; i < count; ++i) {
        uint8_t& s = slot_face[after[i] % kSlots];
        hashed &= s == 0xff;
        s = uint8_t(i);
    }
    // Walk from face 0 to the face that starts where this one ends. Returning to
    // face 0 first after exactly `count` steps means every face was visited once.
    uint32_t i = 0;
    for (size_t t = 0; t < count; ++t) {
        at[t] = uint8_t(i);
        ring[t] = after[i];
        uint32_t next = slot_face[before[i] % kSlots];
        if (!hashed) {
            next = 0;
            while (next < count && after[next] != before[i]) ++next;
        }
        if (next >= count || after[next] != before[i]) return 0;
        if (next == 0) return t + 1 == count ? count : 0;
        i = next;
    }
    return 0;
}

bool SplitReplay::apply_mask(uint32_t parent, uint32_t child, uint64_t mask, size_t moving, const uint32_t* corners,
                             size_t count, uint32_t* moved) {
    if (count < 64 && (mask >> count) != 0) return false;
    if (parent >= regions_.size()) grow_regions(parent);
    uint32_t* to = make_room(child, region(child).count + moving + 2);  // + the split's new faces
    uint32_t* from = pool_.data() + regions_[parent].offset;            // after make_room: the pool may have moved
    uint32_t kept = 0, m = regions_[child].count;
    // Without branches (the mask's bits are unpredictable): every corner is
    // written to both lists, and only the list it belongs to moves on.
    for (size_t i = 0; i < count; ++i) {
        const uint32_t c = corners[i], moves = (uint32_t(mask >> (i & 63)) & 1u) & uint32_t(i < 64);
        indices_[c] ^= (indices_[c] ^ child) & (0u - moves);  // a mask, not a select: GCC made that a branch
        to[m] = c;
        from[kept] = c;
        m += moves;
        kept += 1 - moves;
    }
    std::copy_n(to + regions_[child].count, moving, moved);
    regions_[child].count = m;
    regions_[parent].count = kept;
    return true;
}

bool SplitReplay::apply_mask(uint32_t parent, uint32_t child, uint64_t mask, std::vector<uint32_t>& scratch,
                             std::vector<uint32_t>& moved) {
    corners_of(parent, scratch);
    moved.resize(scratch.size());
    if (!apply_mask(parent, child, mask, size_t(std::popcount(mask)), scratch.data(), scratch.size(), moved.data())) {
        moved.clear();
        return false;
    }
    moved.resize(size_t(std::popcount(mask)));
    return true;
}

void SplitReplay::prefetch(uint32_t v, int stage, const uint16_t* qpos, const uint32_t* per_vertex,
                           const uint32_t* per_face) const {
#if defined(__GNUC__)
    if (v >= regions_.size()) return;  // a vertex not arrived yet: nothing to fetch
    if (stage == 0) {
        __builtin_prefetch(&regions_[v]);
        return;
    }
    const Region r = regions_[v];
    if (stage == 1) {
        __builtin_prefetch(pool_.data() + r.offset);
        if (r.count > 12) __builtin_prefetch(pool_.data() + r.offset + 16);
        return;
    }
    const uint32_t* c = pool_.data() + r.offset;
    if (stage == 2) {
        for (uint32_t i = 0; i < r.count && i < 16; ++i) {
            __builtin_prefetch(&indices_[c[i] / 3 * 3]);
            if (per_face) __builtin_prefetch(per_face + c[i] / 3);
        }
        return;
    }
    // Stage 3: the neighbours' regions (a new face adds a corner to one of them).
    for (uint32_t i = 0; i < r.count && i < 16; ++i) {
        const uint32_t* t = &indices_[c[i] / 3 * 3];
        // The vertex after v in each face: every neighbour once around an interior vertex.
        const uint32_t n = t[kNextCorner[c[i] - c[i] / 3 * 3]];
        if (n < regions_.size()) __builtin_prefetch(&regions_[n]);
        if (qpos) __builtin_prefetch(qpos + size_t(n) * 3);
        if (per_vertex) __builtin_prefetch(per_vertex + n);
    }
#else
    (void)v;
    (void)stage;
    (void)qpos;
    (void)per_vertex;
    (void)per_face;
#endif
}

}  // namespace body::pm
