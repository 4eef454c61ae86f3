#pragma once
// The draw order of a progressive mesh's faces: refinement in batches.
//
// Splits append their faces in refinement order, which the simplifier chose by
// cost all over the surface, so consecutive faces rarely share a vertex and a
// GPU's post-transform cache barely hits (2.5x a cache-optimised static mesh on
// an H100). The reader therefore groups the splits into batches at geometric
// level boundaries (vertex counts B, B r, B r^2, ... N + B, r = kBatchRatio) and,
// once a batch is decoded, reorders the batch's faces among themselves for the
// vertex cache on its connectivity at the batch's last level and numbers the
// batch's vertices among themselves in the order those faces first use them
// (first_use_order, for vertex fetch) (cache_order:
// a Morton sort, then meshopt_optimizeVertexCache in windows; over whole
// batches it made decoding 2.5-2.9x slower, see bench/RESULTS.md). Every boundary level is then a prefix made of
// cache-ordered runs, the newest run the largest (about (r-1)/r of the faces).
// The price: only boundary levels (and the levels of the batch still
// arriving) are exact prefixes, so a level is chosen at batch boundaries and
// the kiosk's geomorphs glide over a step. This is the "refine in batches,
// optimise each batch" scheme of sequential-PM renderers (e.g. Hoppe 1999,
// "Optimization of mesh locality for transparent vertex caching", applied per
// batch); it needs no bytes in the file, since the order is a deterministic
// function of the decoded connectivity.
// Limit (measured, issue 24): a prefix layout cannot reach a static mesh's
// locality. A batch's new faces are mostly pairs around separate split edges
// and the older faces around a split are patched in place, so ACMR (cache 16)
// falls from 2.38 (refinement order) to about 1.6 on the bunny, against 0.68 for
// the same triangles through meshoptimizer. Closing that needs faces
// re-emitted in the newest batch or a per-level reordered element buffer.
// Likewise fetch: each batch's run sweeps the whole surface once, so vertex
// fetch overfetch (meshopt, 128 KiB) stays about 4-5 against 1.1-1.2 for the
// static mesh (it was 10-11 with vertices in split order).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shared/pm/cache_window.h"
#include "shared/pm/large_array.h"

namespace body::pm {

// Ratio of the vertex counts at consecutive batch boundaries.
inline constexpr double kBatchRatio = 2.0;

// The batch boundary levels (split counts) of a mesh of `base_vertices` + `splits`
// vertices: ascending, the last == splits, none 0 (level 0 is always a boundary).
std::vector<uint32_t> batch_levels(size_t base_vertices, size_t splits);

// Working memory of cache_order, caller-owned and reused between calls (its
// contents belong to cache_order: local_of stays all UINT32_MAX between calls).
// The batch arrays are the caller's (ProgressiveMesh::order_batch), uninitialised:
// each batch writes what it reads, so a larger batch neither zeroes nor copies them.
struct CacheOrderScratch {
    UninitVector<uint64_t> keys;
    CacheWindowScratch window;
    UninitVector<uint32_t> faces, order, number, ordered;
    // Frees the batch arrays (the reader: at the end of each feed).
    void release_batch_arrays() {
        for (auto* v : {&faces, &order, &number, &ordered}) UninitVector<uint32_t>().swap(*v);
    }
};

// The cache order of `face_count` triangles (`indices`, three per face, each <
// vertex_count; `qpos`: 3 position codes per vertex): writes to order[i] the
// face drawn i-th (a permutation of 0 .. face_count-1). The faces sorted stably
// by the Morton code of their first corner (10 bits per axis), then windows of
// 1024 consecutive faces each through cache_order_window (cache_window.h; a
// window's tables stay in the CPU's caches; Tipsify there instead decoded
// faster still, at 5 % more cache misses).
void cache_order(const uint32_t* indices, size_t face_count, size_t vertex_count, const uint16_t* qpos, uint32_t* order,
                 CacheOrderScratch& scratch);

// Numbers the vertices [first, first + count) in the order `indices` first use
// them: number[k] is the new number of vertex first + k, a permutation of
// [first, first + count) (vertices the indices never use come last, in their
// order). The vertex fetch order of meshopt_optimizeVertexFetchRemap restricted
// to one batch's vertices, so a batch's renumbering leaves every other number alone.
void first_use_order(const uint32_t* indices, size_t index_count, uint32_t first, uint32_t count, uint32_t* number);

}  // namespace body::pm
