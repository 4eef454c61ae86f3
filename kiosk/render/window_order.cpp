// Vertex-cache order in bounded windows (see window_order.h): check, bucket
// sort in place by cell, then each window through pm::cache_order_window.
#include "kiosk/render/window_order.h"

#include <algorithm>
#include <bit>
#include <numeric>
#include <utility>
#include <vector>

#include "shared/pm/cache_window.h"

namespace body::render {
namespace {

constexpr size_t kCells = size_t{1} << kOrderCellBits;

// Whether order_in_windows may order `indices` over `cells`.
bool orderable(std::span<const uint32_t> indices, std::span<const uint16_t> cells) {
    if (indices.size() % 3 != 0) return false;
    if (std::any_of(indices.begin(), indices.end(), [&](uint32_t i) { return i >= cells.size(); })) return false;
    return std::none_of(cells.begin(), cells.end(), [](uint16_t c) { return c >= kCells; });
}

bool cancelled(const std::atomic<bool>* cancel) { return cancel && cancel->load(std::memory_order_relaxed); }

// Bucket bounds of the triangles by their first corner's cell: start[c] (kCells + 1 entries) and next[c] = start[c],
// the bucket's next unplaced triangle.
void count_buckets(std::span<const uint32_t> idx, std::span<const uint16_t> cells, std::vector<uint32_t>& start,
                   std::vector<uint32_t>& next) {
    const size_t faces = idx.size() / 3;
    start.assign(kCells + 1, 0);
    for (size_t f = 0; f < faces; ++f) ++start[cells[idx[3 * f]] + size_t{1}];
    for (size_t c = 0; c < kCells; ++c) start[c + 1] += start[c];
    next.assign(start.begin(), start.end() - 1);
}

// American flag sort, resumable: from bucket `bucket` on, triangle records are moved into their cell's bucket by
// swap(f, g) (each swap placing one for good), until every bucket is full or about `budget` records were looked at
// (then `bucket` is where to resume). Returns the records looked at.
template <class Swap>
size_t fill_buckets(std::span<const uint32_t> idx, std::span<const uint16_t> cells, const std::vector<uint32_t>& start,
                    std::vector<uint32_t>& next, size_t& bucket, size_t budget, Swap&& swap) {
    size_t spent = 0;
    while (bucket < kCells && spent < budget) {
        const size_t b = bucket;
        if (next[b] >= start[b + 1]) {
            ++bucket;
            continue;
        }
        ++spent;
        const size_t f = next[b];
        const uint16_t c = cells[idx[3 * f]];
        if (c == b) {
            ++next[b];
            continue;
        }
        swap(f, size_t(next[c]++));
    }
    return spent;
}

// The next window of whole cells from cell `cell` on (at least kOrderWindowFaces triangles, or up to the last cell):
// [begin, end) in triangles, `cell` and `begin` advanced past it. False when no cell is left.
bool next_window(const std::vector<uint32_t>& start, size_t window_faces, size_t& cell, size_t& begin, size_t& a,
                 size_t& b) {
    while (cell <= kCells) {
        const size_t c = cell++;
        if (start[c] - begin < window_faces && c < kCells) continue;
        a = begin;
        b = begin = start[c];
        return true;
    }
    return false;
}

}  // namespace

uint16_t order_cell(float tx, float ty, float tz) {
    const auto axis = [](float t) {
        if (!(t > 0.0f)) return 0u;  // also NaN
        const float c = std::min(t, 1.0f) * 32.0f;
        return std::min(static_cast<uint32_t>(c), 31u);
    };
    return static_cast<uint16_t>(pm::morton_code(axis(tx), axis(ty), axis(tz)));
}

bool order_in_windows(std::span<uint32_t> indices, std::span<const uint16_t> cells, const std::atomic<bool>* cancel,
                      size_t window_faces) {
    if (window_faces == 0 || !orderable(indices, cells)) return false;
    std::vector<uint32_t> start, next;
    count_buckets(indices, cells, start, next);
    const auto swap = [&](size_t f, size_t g) {
        for (size_t k = 0; k < 3; ++k) std::swap(indices[3 * f + k], indices[3 * g + k]);
    };
    for (size_t bucket = 0; bucket < kCells;) {
        if (cancelled(cancel)) return false;
        fill_buckets(indices, cells, start, next, bucket, size_t{1} << 16, swap);
    }
    pm::CacheWindowScratch w;
    size_t cell = 1, begin = 0, a = 0, b = 0;
    while (next_window(start, window_faces, cell, begin, a, b)) {
        if (b == a) continue;
        if (cancelled(cancel)) return false;
        pm::reserve_cache_window(w, b - a, cells.size());  // whole cells: may pass window_faces
        pm::cache_order_window(indices.data() + 3 * a, b - a, w);
    }
    return true;
}

void PackedPermutation::identity(size_t n) {
    size_ = n;
    bits_ = n > 1 ? unsigned(std::bit_width(n - 1)) : 1u;
    mask_ = (uint64_t{1} << bits_) - 1;
    words_.assign((n * bits_ + 63) / 64 + 1, 0);  // + 1: an entry's high word is always there
    for (size_t i = 0; i < n; ++i) set(i, uint32_t(i));
}

void PackedPermutation::clear() {
    std::vector<uint64_t>().swap(words_);
    size_ = 0;
}

namespace {

void swap_triangles(std::span<uint32_t> idx, PackedPermutation& perm, size_t f, size_t g) {
    for (size_t k = 0; k < 3; ++k) std::swap(idx[3 * f + k], idx[3 * g + k]);
    perm.swap(f, g);
}

// s.moved = the window's corners numbered 0, 1, ... in the order they are
// first used (the numbers the kernel gives them anyway), found by sorting the
// corners, not through a map over every vertex of the mesh; the count.
uint32_t number_window(SlicedOrder& s, const uint32_t* tri, size_t corners) {
    s.corners.resize(corners);
    std::iota(s.corners.begin(), s.corners.end(), 0u);
    std::sort(s.corners.begin(), s.corners.end(),
              [&](uint32_t x, uint32_t y) { return tri[x] < tri[y] || (tri[x] == tri[y] && x < y); });
    s.firsts.clear();  // per vertex: its first corner, and where its run starts in s.corners
    for (size_t i = 0; i < corners; ++i)
        if (i == 0 || tri[s.corners[i]] != tri[s.corners[i - 1]]) s.firsts.push_back(uint64_t{s.corners[i]} << 32 | i);
    std::sort(s.firsts.begin(), s.firsts.end());
    s.moved.resize(corners);
    for (size_t l = 0; l < s.firsts.size(); ++l) {
        const uint32_t v = tri[s.firsts[l] >> 32];
        for (size_t i = uint32_t(s.firsts[l]); i < corners && tri[s.corners[i]] == v; ++i)
            s.moved[s.corners[i]] = uint32_t(l);
    }
    return uint32_t(s.firsts.size());
}

// One window [a, b) through the kernel's permutation form (the in-place form's
// order), its triangles and their perm entries moved alike.
void order_window(SlicedOrder& s, std::span<uint32_t> idx, size_t a, size_t b) {
    const size_t n = b - a;
    uint32_t* tri = idx.data() + 3 * a;
    const uint32_t nv = number_window(s, tri, 3 * n);
    pm::reserve_cache_window(s.scratch, n, nv);  // whole cells: may pass kOrderWindowFaces
    s.faces.resize(n);
    std::iota(s.faces.begin(), s.faces.end(), 0u);
    if (!pm::cache_order_window(s.moved.data(), s.faces.data(), n, s.scratch)) return;  // left in cell order
    s.moved.resize(n);
    for (size_t t = 0; t < n; ++t) s.moved[t] = s.perm[a + t];
    for (size_t t = 0; t < n; ++t) s.perm.set(a + t, s.moved[s.faces[t]]);
    s.moved.assign(tri, tri + 3 * n);
    for (size_t t = 0; t < n; ++t)
        for (size_t k = 0; k < 3; ++k) tri[3 * t + k] = s.moved[3 * size_t(s.faces[t]) + k];
}

template <class V>
void free_vector(V& v) {
    V().swap(v);
}

}  // namespace

bool begin_sliced_order(SlicedOrder& s, std::span<const uint32_t> indices, std::vector<uint16_t> cells) {
    s = SlicedOrder{};
    if (!orderable(indices, cells) || indices.size() / 3 >= UINT32_MAX) return false;
    count_buckets(indices, cells, s.start, s.next);
    s.perm.identity(indices.size() / 3);
    s.cells = std::move(cells);
    s.begun = true;
    return true;
}

bool step_sliced_order(SlicedOrder& s, std::span<uint32_t> idx, size_t budget) {
    if (!s.begun || s.finished || idx.size() != 3 * s.perm.size()) return s.finished;
    // The bucket sort of order_in_windows, resumed where it stopped.
    size_t spent = fill_buckets(idx, s.cells, s.start, s.next, s.bucket, budget,
                                [&](size_t f, size_t g) { swap_triangles(idx, s.perm, f, g); });
    // Then its windows of whole cells (the cells are not read again: only their count).
    if (s.bucket >= kCells && !s.cells.empty()) {
        s.vertex_count = s.cells.size();
        free_vector(s.cells);
        free_vector(s.next);
    }
    for (size_t a = 0, b = 0; s.bucket >= kCells && spent < budget &&
                              next_window(s.start, kOrderWindowFaces, s.window_cell, s.window_begin, a, b);) {
        if (b > a) order_window(s, idx, a, b);
        spent += b - a + 1;
    }
    if (s.bucket < kCells || s.window_cell <= kCells) return false;
    s.finished = true;
    free_vector(s.cells);
    free_vector(s.start);
    free_vector(s.next);
    free_vector(s.faces);
    free_vector(s.moved);
    free_vector(s.corners);
    free_vector(s.firsts);
    s.scratch = pm::CacheWindowScratch{};
    return true;
}

void restore_order(std::span<uint32_t> indices, PackedPermutation& perm) {
    const size_t n = std::min(perm.size(), indices.size() / 3);
    // Cycle by cycle: the triangle at i goes to perm[i]; an entry that names
    // its own position is home (placed ones are set so).
    for (size_t i = 0; i < n; ++i) {
        if (perm[i] == i) continue;
        uint32_t carry[3] = {indices[3 * i], indices[3 * i + 1], indices[3 * i + 2]};
        size_t j = perm[i];
        perm.set(i, uint32_t(i));
        for (;;) {
            for (size_t k = 0; k < 3; ++k) std::swap(carry[k], indices[3 * j + k]);
            if (j == i) break;
            const size_t next = perm[j];
            perm.set(j, uint32_t(j));
            j = next;
        }
    }
    perm.clear();
}

}  // namespace body::render
