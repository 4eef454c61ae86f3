// Vertex-cache order in bounded windows (see window_order.h): check, bucket
// sort in place by cell, then each window through pm::cache_order_window.
#include "kiosk/render/window_order.h"

#include <algorithm>
#include <utility>
#include <vector>

#include "shared/pm/cache_window.h"

namespace body::render {
namespace {

constexpr size_t kCells = size_t{1} << kOrderCellBits;

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
    if (indices.size() % 3 != 0 || window_faces == 0) return false;
    if (std::any_of(indices.begin(), indices.end(), [&](uint32_t i) { return i >= cells.size(); })) return false;
    if (std::any_of(cells.begin(), cells.end(), [](uint16_t c) { return c >= kCells; })) return false;
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

}  // namespace body::render
