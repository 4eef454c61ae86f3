// One window in vertex-cache order (contract in cache_window.h): the window's
// vertices numbered locally, meshopt_optimizeVertexCache, then the result as
// a permutation of the input faces or written over the triangles.
#include "shared/pm/cache_window.h"

#include <meshoptimizer.h>

#include <algorithm>

namespace body::pm {
namespace {

// s.local[0 .. 3 n) = the corners corner(t, k) numbered in the order they
// first appear, s.global[0 .. nv) = the vertex of each local number; returns nv.
// s.local_of is all UINT32_MAX on entry and on return.
template <class Corner>
uint32_t number_locally(size_t n, Corner corner, CacheWindowScratch& s) {
    uint32_t nv = 0;
    for (size_t t = 0; t < n; ++t)
        for (size_t k = 0; k < 3; ++k) {
            // Without branches (whether a vertex is new is unpredictable): global[nv]
            // is written every time and kept only when nv moves on.
            const uint32_t v = corner(t, k), known = s.local_of[v];
            const uint32_t fresh = 0u - uint32_t(known == UINT32_MAX);  // all ones or 0
            s.global[nv] = v;
            const uint32_t local = known ^ ((known ^ nv) & fresh);
            s.local_of[v] = local;
            s.local[t * 3 + k] = local;
            nv -= fresh;  // + 1 when fresh
        }
    for (uint32_t v = 0; v < nv; ++v) s.local_of[s.global[v]] = UINT32_MAX;
    return nv;
}

// s.window[t] = the input face (0 .. n) of the t-th triangle meshopt emitted
// in s.sorted, matched through the faces listed by their first corner (a CSR
// over the window's nv vertices); false when one has no unused match.
bool match_faces(size_t n, uint32_t nv, CacheWindowScratch& s) {
    uint32_t* start = s.start.data();
    uint32_t* by_first = s.by_first.data();
    const uint32_t* local = s.local.data();
    const uint32_t* sorted = s.sorted.data();
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
        if (window[t] == UINT32_MAX) return false;
    }
    return true;
}

}  // namespace

void reserve_cache_window(CacheWindowScratch& s, size_t window_faces, size_t vertex_count) {
    if (s.local_of.size() < vertex_count) s.local_of.resize(vertex_count, UINT32_MAX);
    const size_t corners = 3 * window_faces;
    if (s.local.size() < corners)
        for (auto* v : {&s.local, &s.sorted, &s.global}) v->resize(corners);
}

bool cache_order_window(const uint32_t* indices, uint32_t* faces, size_t n, CacheWindowScratch& s) {
    const uint32_t nv = number_locally(
        n, [&](size_t t, size_t k) { return indices[size_t(faces[t]) * 3 + k]; }, s);
    meshopt_optimizeVertexCache(s.sorted.data(), s.local.data(), n * 3, nv);
    if (s.window.size() < n) {  // the matching's scratch, only this form's
        s.start.resize(3 * n + 1);
        s.by_first.resize(n);
        s.window.resize(n);
    }
    if (!match_faces(n, nv, s)) return false;
    uint32_t* window = s.window.data();
    for (size_t t = 0; t < n; ++t) window[t] = faces[window[t]];
    std::copy_n(window, n, faces);
    return true;
}

void cache_order_window(uint32_t* triples, size_t n, CacheWindowScratch& s) {
    const uint32_t nv = number_locally(
        n, [&](size_t t, size_t k) { return triples[t * 3 + k]; }, s);
    meshopt_optimizeVertexCache(s.sorted.data(), s.local.data(), n * 3, nv);
    for (size_t i = 0; i < n * 3; ++i) triples[i] = s.global[s.sorted[i]];
}

}  // namespace body::pm
