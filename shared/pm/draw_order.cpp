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

void cache_order(const uint32_t* indices, size_t face_count, size_t vertex_count, uint32_t* order,
                 std::vector<uint32_t>& scratch) {
    // meshopt reorders index triples (copied corner for corner); each output
    // triangle is matched back to an unused input face through the faces listed
    // by their first corner's vertex (a CSR over the batch's first corners).
    const size_t n = face_count * 3;
    scratch.resize(n + face_count + vertex_count + 1);
    uint32_t* sorted = scratch.data();
    uint32_t* by_first = sorted + n;
    uint32_t* start = by_first + face_count;
    meshopt_optimizeVertexCache(sorted, indices, n, vertex_count);
    std::fill(start, start + vertex_count + 1, 0u);
    for (size_t f = 0; f < face_count; ++f) ++start[indices[f * 3] + 1];
    for (size_t v = 0; v < vertex_count; ++v) start[v + 1] += start[v];
    for (size_t f = 0; f < face_count; ++f) by_first[start[indices[f * 3]]++] = uint32_t(f);
    // start[v] is now the end of v's list; its beginning is start[v - 1] (0 for v = 0).
    bool matched = true;
    for (size_t t = 0; t < face_count; ++t) {
        order[t] = UINT32_MAX;
        const uint32_t a = sorted[t * 3], b = sorted[t * 3 + 1], c = sorted[t * 3 + 2];
        const uint32_t begin = a == 0 ? 0 : start[a - 1];
        for (uint32_t i = begin; i < start[a]; ++i) {
            const uint32_t f = by_first[i];
            if (f != UINT32_MAX && indices[f * 3 + 1] == b && indices[f * 3 + 2] == c) {
                order[t] = f;
                by_first[i] = UINT32_MAX;  // used
                break;
            }
        }
        matched = matched && order[t] != UINT32_MAX;
    }
    // meshopt emits its input's triangles; should one not match, keep the input order.
    if (!matched)
        for (size_t f = 0; f < face_count; ++f) order[f] = uint32_t(f);
}

}  // namespace body::pm
