// Batch boundaries and the per-batch cache order (contract in draw_order.h).
#include "shared/pm/draw_order.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>

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

// Faces per window of the cache optimiser (a window's tables stay in L1/L2).
constexpr size_t kWindowFaces = 1024;

// Bits 0..9 of x spread to every third bit (one axis of a Morton code).
uint32_t spread3(uint32_t x) {
    x &= 0x3ff;
    x = (x | (x << 16)) & 0x30000ff;
    x = (x | (x << 8)) & 0x300f00f;
    x = (x | (x << 4)) & 0x30c30c3;
    x = (x | (x << 2)) & 0x9249249;
    return x;
}

// order[0 .. face_count) = the faces by the Morton code of their first corner
// (10 bits per axis; the faces of one split share it and stay together):
// a stable LSD radix sort of (code << 32 | face), 3 passes of 10 bits.
void sort_spatially(const uint32_t* indices, size_t face_count, const uint16_t* qpos, uint32_t* order,
                    CacheOrderScratch& s) {
    s.keys.resize(2 * face_count);
    uint64_t* a = s.keys.data();
    uint64_t* b = a + face_count;
    for (size_t f = 0; f < face_count; ++f) {
        const uint16_t* p = qpos + size_t(indices[f * 3]) * 3;
        const uint32_t code = spread3(p[0] >> 6) | spread3(p[1] >> 6) << 1 | spread3(p[2] >> 6) << 2;
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

// Reorders the faces order[0 .. n) (n <= kWindowFaces) for the vertex cache.
// The window's vertices are numbered densely first (s.local_of is all
// UINT32_MAX on entry and on return). meshopt copies index triples corner for
// corner; each output triangle is matched back to an unused input face through
// the faces listed by their first corner (a CSR over the window's vertices).
void optimise_window(const uint32_t* indices, uint32_t* order, size_t n, CacheOrderScratch& s) {
    uint32_t nv = 0;
    for (size_t t = 0; t < n; ++t)
        for (size_t k = 0; k < 3; ++k) {
            // Without branches (whether a vertex is new is unpredictable): global[nv]
            // is written every time and kept only when nv moves on.
            const uint32_t v = indices[size_t(order[t]) * 3 + k], known = s.local_of[v];
            const uint32_t fresh = 0u - uint32_t(known == UINT32_MAX);  // all ones or 0
            s.global[nv] = v;
            const uint32_t local = known ^ ((known ^ nv) & fresh);
            s.local_of[v] = local;
            s.local[t * 3 + k] = local;
            nv -= fresh;  // + 1 when fresh
        }
    for (uint32_t v = 0; v < nv; ++v) s.local_of[s.global[v]] = UINT32_MAX;
    uint32_t* sorted = s.sorted.data();
    uint32_t* start = s.start.data();
    uint32_t* by_first = s.by_first.data();
    const uint32_t* local = s.local.data();
    meshopt_optimizeVertexCache(sorted, local, n * 3, nv);
    std::fill(start, start + nv + 1, 0u);
    for (size_t f = 0; f < n; ++f) ++start[local[f * 3] + 1];
    for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
    for (size_t f = 0; f < n; ++f) by_first[start[local[f * 3]]++] = uint32_t(f);
    // start[v] is now the end of v's list; its beginning is start[v - 1] (0 for v = 0).
    uint32_t* window = s.window.data();
    for (size_t t = 0; t < n; ++t) {
        window[t] = UINT32_MAX;
        const uint32_t a = sorted[t * 3], b = sorted[t * 3 + 1], c = sorted[t * 3 + 2];
        for (uint32_t i = a == 0 ? 0 : start[a - 1]; i < start[a]; ++i) {
            const uint32_t f = by_first[i];
            if (f != UINT32_MAX && local[f * 3 + 1] == b && local[f * 3 + 2] == c) {
                window[t] = f;
                by_first[i] = UINT32_MAX;  // used
                break;
            }
        }
        // meshopt emits its input's triangles; should one not match, keep the window as it is.
        if (window[t] == UINT32_MAX) return;
    }
    for (size_t t = 0; t < n; ++t) window[t] = order[window[t]];
    std::copy_n(window, n, order);
}

}  // namespace

void cache_order(const uint32_t* indices, size_t face_count, size_t vertex_count, const uint16_t* qpos, uint32_t* order,
                 CacheOrderScratch& scratch) {
    sort_spatially(indices, face_count, qpos, order, scratch);
    // Every entry is UINT32_MAX between windows (optimise_window restores them):
    // only the new vertices' entries are written.
    if (scratch.local_of.size() < vertex_count) scratch.local_of.resize(vertex_count, UINT32_MAX);
    for (auto* v : {&scratch.local, &scratch.sorted, &scratch.global}) v->resize(3 * kWindowFaces);
    scratch.start.resize(3 * kWindowFaces + 1);
    scratch.by_first.resize(kWindowFaces);
    scratch.window.resize(kWindowFaces);
    for (size_t w = 0; w < face_count; w += kWindowFaces)
        optimise_window(indices, order + w, std::min(kWindowFaces, face_count - w), scratch);
}

void first_use_order(const uint32_t* indices, size_t index_count, uint32_t first, uint32_t count, uint32_t* number) {
    std::fill(number, number + count, UINT32_MAX);
    uint32_t next = first;
    if (count == 0) return;
    // Without branches (whether a vertex is new is unpredictable): a vertex
    // outside the range reads and rewrites entry 0 unchanged.
    for (size_t i = 0; i < index_count; ++i) {
        const uint32_t k = indices[i] - first;  // wraps above count for a vertex below first
        const uint32_t inside = 0u - uint32_t(k < count), at = k & inside;
        const uint32_t fresh = inside & (0u - uint32_t(number[at] == UINT32_MAX));  // all ones or 0
        number[at] ^= (number[at] ^ next) & fresh;
        next -= fresh;  // + 1 when fresh
    }
    for (uint32_t k = 0; k < count; ++k)
        if (number[k] == UINT32_MAX) number[k] = next++;
}

}  // namespace body::pm
