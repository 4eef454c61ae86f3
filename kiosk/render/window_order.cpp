// Vertex-cache order in bounded windows (see window_order.h): check, bucket
// sort in place by cell, then each window through meshoptimizer.
#include "kiosk/render/window_order.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace body::render {
namespace {

constexpr size_t kCells = size_t{1} << kOrderCellBits;

// Bits 0..4 of x spread to every third bit (one axis of the Morton code).
uint32_t spread3(uint32_t x) {
    x &= 0x1f;
    x = (x | (x << 8)) & 0x0f00f;
    x = (x | (x << 4)) & 0xc30c3;
    x = (x | (x << 2)) & 0x249249;
    return x;
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

// Scratch of one window, reused: local numbers of the global vertices.
struct Window {
    std::vector<uint32_t> local_of;  // global -> local, UINT32_MAX when not in the window
    std::vector<uint32_t> global, local, out;
};

// The triangles idx[3 a, 3 b) in meshoptimizer's cache order, in place.
void order_window(std::span<uint32_t> idx, size_t a, size_t b, Window& w) {
    w.global.clear();
    w.local.resize(3 * (b - a));
    for (size_t i = 3 * a; i < 3 * b; ++i) {
        uint32_t& l = w.local_of[idx[i]];
        if (l == UINT32_MAX) {
            l = static_cast<uint32_t>(w.global.size());
            w.global.push_back(idx[i]);
        }
        w.local[i - 3 * a] = l;
    }
    w.out.resize(w.local.size());
    meshopt_optimizeVertexCache(w.out.data(), w.local.data(), w.local.size(), w.global.size());
    for (size_t i = 0; i < w.out.size(); ++i) idx[3 * a + i] = w.global[w.out[i]];
    for (uint32_t g : w.global) w.local_of[g] = UINT32_MAX;
}

}  // namespace

uint16_t order_cell(float tx, float ty, float tz) {
    const auto axis = [](float t) {
        if (!(t > 0.0f)) return 0u;  // also NaN
        const float c = std::min(t, 1.0f) * 32.0f;
        return std::min(static_cast<uint32_t>(c), 31u);
    };
    return static_cast<uint16_t>(spread3(axis(tx)) | spread3(axis(ty)) << 1 | spread3(axis(tz)) << 2);
}

bool order_in_windows(std::span<uint32_t> indices, std::span<const uint16_t> cells, const std::atomic<bool>* cancel,
                      size_t window_faces) {
    if (indices.size() % 3 != 0 || window_faces == 0) return false;
    if (std::any_of(indices.begin(), indices.end(), [&](uint32_t i) { return i >= cells.size(); })) return false;
    if (std::any_of(cells.begin(), cells.end(), [](uint16_t c) { return c >= kCells; })) return false;
    std::vector<uint32_t> start;
    if (!sort_by_cell(indices, cells, start, cancel)) return false;
    Window w;
    w.local_of.assign(cells.size(), UINT32_MAX);
    // Whole buckets per window (a cell's triangles stay together).
    size_t a = 0;
    for (size_t c = 1; c <= kCells; ++c) {
        const size_t b = start[c];
        if (b - a < window_faces && c < kCells) continue;
        if (b > a) {
            if (cancelled(cancel)) return false;
            order_window(indices, a, b, w);
        }
        a = b;
    }
    return true;
}

}  // namespace body::render
