// Batch boundaries and the per-batch cache order (contract in draw_order.h).
#include "shared/pm/draw_order.h"

#include <algorithm>
#include <cmath>

#include "shared/pm/cache_window.h"

namespace body::pm {

std::vector<uint32_t> batch_levels(size_t base_vertices, size_t splits) {
    std::vector<uint32_t> out;
    const double total = double(base_vertices + splits);
    // At least 64 splits a batch so a tiny mesh is not cut into single splits.
    for (double v = double(base_vertices) * kBatchRatio; v < total; v *= kBatchRatio) {
        const size_t level = size_t(std::llround(v)) - base_vertices;
        if (level >= splits) break;
        if (level >= (out.empty() ? 0 : out.back()) + 64) out.push_back(uint32_t(level));
    }
    if (splits > 0) out.push_back(uint32_t(splits));
    return out;
}

namespace {

// morton_spread3 of every 10-bit value: a face's Morton code is three loads.
struct SpreadTable {
    uint32_t spread[1024] = {};
    constexpr SpreadTable() {
        for (uint32_t x = 0; x < 1024; ++x) spread[x] = morton_spread3(x);
    }
};
constexpr SpreadTable kSpread;

// order[0 .. face_count) = the faces by the Morton code of their first corner
// (10 bits per axis; the faces of one split share it and stay together):
// a stable LSD radix sort of (code << 32 | face), 3 passes of 10 bits.
void sort_spatially(const uint32_t* indices, size_t face_count, const uint16_t* qpos, uint32_t* order,
                    CacheOrderScratch& s) {
    s.keys.clear();  // no copy of the last batch's keys when it grows
    s.keys.resize(2 * face_count);
    uint64_t* a = s.keys.data();
    uint64_t* b = a + face_count;
    const uint32_t* spread = kSpread.spread;
    for (size_t f = 0; f < face_count; ++f) {
        if (f + kGatherAhead < face_count) prefetch(qpos + size_t(indices[(f + kGatherAhead) * 3]) * 3);
        const uint16_t* p = qpos + size_t(indices[f * 3]) * 3;
        const uint32_t code = spread[p[0] >> 6] | spread[p[1] >> 6] << 1 | spread[p[2] >> 6] << 2;  // morton_code
        a[f] = uint64_t(code) << 32 | f;
    }
    for (uint32_t shift = 32; shift < 62; shift += 10) {
        uint32_t count[1025] = {};
        for (size_t i = 0; i < face_count; ++i) ++count[((a[i] >> shift) & 1023) + 1];
        for (size_t i = 0; i < 1024; ++i) count[i + 1] += count[i];
        for (size_t i = 0; i < face_count; ++i) b[count[(a[i] >> shift) & 1023]++] = a[i];
        std::swap(a, b);
    }
    for (size_t t = 0; t < face_count; ++t) order[t] = uint32_t(a[t]);
}

}  // namespace

void cache_order(const uint32_t* indices, size_t face_count, const uint16_t* qpos, uint32_t* order,
                 CacheOrderScratch& scratch) {
    sort_spatially(indices, face_count, qpos, order, scratch);
}

void first_use_order(const uint32_t* indices, const uint32_t* order, size_t face_count, uint32_t first, uint32_t count,
                     uint32_t* number) {
    std::fill(number, number + count, UINT32_MAX);
    uint32_t next = first;
    if (count == 0) return;
    // Without branches (whether a vertex is new is unpredictable): a vertex
    // outside the range reads and rewrites entry 0 unchanged.
    for (size_t t = 0; t < face_count; ++t) {
        if (t + kGatherAhead < face_count) prefetch(indices + size_t(order[t + kGatherAhead]) * 3);
        const uint32_t* corners = indices + size_t(order[t]) * 3;
        for (size_t i = 0; i < 3; ++i) {
            const uint32_t k = corners[i] - first;  // wraps above count for a vertex below first
            const uint32_t inside = 0u - uint32_t(k < count), at = k & inside;
            const uint32_t fresh = inside & (0u - uint32_t(number[at] == UINT32_MAX));  // all ones or 0
            number[at] ^= (number[at] ^ next) & fresh;
            next -= fresh;  // + 1 when fresh
        }
    }
    for (uint32_t k = 0; k < count; ++k)
        if (number[k] == UINT32_MAX) number[k] = next++;
}

}  // namespace body::pm
