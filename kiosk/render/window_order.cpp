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

// American flag sort: triangle records moved into their cell's bucket by
// swaps, each swap placing one for good. `start`: kCells + 1 bucket bounds.
bool sort_by_cell(std::span<uint32_t> idx, std::span<const uint16_t> cells, std::vector<uint32_t>& start,
                  const std::atomic<bool>* cancel) {
    const size_t faces = idx.size() / 3;
    start.assign(kCells + 1, 0);
    for (size_t f = 0; f < faces; ++f) ++start[cells[idx[3 * f]] + size_t{1}];
    for (size_t c = 0; c < kCells; ++c) start[c + 1] += start[c];
    std::vector<uint32_t> next(start.begin(), start.end() - 1);
    for (size_t b = 0; b < kCells; ++b) {
        if ((b & 1023) == 0 && cancelled(cancel)) return false;
        while (next[b] < start[b + 1]) {
            const size_t f = next[b];
            const uint16_t c = cells[idx[3 * f]];
            if (c == b) {
                ++next[b];
                continue;
            }
            const size_t g = next[c]++;
            for (int k = 0; k < 3; ++k) std::swap(idx[3 * f + k], idx[3 * g + k]);
        }
    }
    return true;
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
    std::vector<uint32_t> start;
    if (!sort_by_cell(indices, cells, start, cancel)) return false;
    pm::CacheWindowScratch w;
    // Whole buckets per window (a cell's triangles stay together).
    size_t a = 0;
    for (size_t c = 1; c <= kCells; ++c) {
        const size_t b = start[c];
        if (b - a < window_faces && c < kCells) continue;
        if (b > a) {
            if (cancelled(cancel)) return false;
            pm::reserve_cache_window(w, b - a, cells.size());  // whole cells: may pass window_faces
            pm::cache_order_window(indices.data() + 3 * a, b - a, w);
        }
        a = b;
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
    const size_t faces = indices.size() / 3;
    s.start.assign(kCells + 1, 0);
    for (size_t f = 0; f < faces; ++f) ++s.start[cells[indices[3 * f]] + size_t{1}];
    for (size_t c = 0; c < kCells; ++c) s.start[c + 1] += s.start[c];
    s.next.assign(s.start.begin(), s.start.end() - 1);
    s.perm.identity(faces);
    s.cells = std::move(cells);
    s.begun = true;
    return true;
}

bool step_sliced_order(SlicedOrder& s, std::span<uint32_t> idx, size_t budget) {
    if (!s.begun || s.finished || idx.size() != 3 * s.perm.size()) return s.finished;
    size_t spent = 0;
    // The bucket sort of order_in_windows, resumed where it stopped.
    while (s.bucket < kCells && spent < budget) {
        const size_t b = s.bucket;
        if (s.next[b] >= s.start[b + 1]) {
            ++s.bucket;
            continue;
        }
        ++spent;
        const size_t f = s.next[b];
        const uint16_t c = s.cells[idx[3 * f]];
        if (c == b) {
            ++s.next[b];
            continue;
        }
        swap_triangles(idx, s.perm, f, s.next[c]++);
    }
    // Then its windows of whole cells (the cells are not read again: only their count).
    if (s.bucket >= kCells && !s.cells.empty()) {
        s.vertex_count = s.cells.size();
        free_vector(s.cells);
        free_vector(s.next);
    }
    while (s.bucket >= kCells && s.window_cell <= kCells && spent < budget) {
        const size_t c = s.window_cell++;
        const size_t a = s.window_begin, b = s.start[c];
        if (b - a < kOrderWindowFaces && c < kCells) continue;
        if (b > a) order_window(s, idx, a, b);
        spent += b - a + 1;
        s.window_begin = b;
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
