#pragma once
// The draw order of a progressive mesh's faces: refinement in batches.
//
// Splits append their faces in refinement order, which the simplifier chose by
// cost all over the surface, so consecutive faces rarely share a vertex and a
// GPU's post-transform cache barely hits (2.5x a cache-optimised static mesh on
// an H100). The reader therefore groups the splits into batches at geometric
// level boundaries (vertex counts B, B r, B r^2, ... N + B, r = kBatchRatio) and,
// once a batch is decoded, sorts the batch's faces among themselves along a
// Morton curve of their first corner (cache_order) on its connectivity at the
// batch's last level and numbers the batch's vertices among themselves in the
// order those faces first use them (first_use_order, for vertex fetch). Every
// boundary level is then a prefix made of spatially sorted runs, the newest run
// the largest (about (r-1)/r of the faces).
// The price: only boundary levels (and the levels of the batch still
// arriving) are exact prefixes, so a level is chosen at batch boundaries and
// the kiosk's geomorphs glide over a step. It needs no bytes in the file, since
// the order is a deterministic function of the decoded connectivity.
// What the kiosk draws once a level settles is not this prefix but a copy
// ordered for the vertex cache over the whole level (kiosk/render/level_order.h,
// near a static mesh's ACMR); the prefix is drawn only for the few frames
// before that and for levels under kMinOrderedTriangles. So the decoder keeps
// only the cheap part of a cache order: meshopt_optimizeVertexCache per
// 1024-face window after the sort bought ACMR 1.80 -> 1.61 on those frames for
// 30 % of the bunny's decode, and changed nothing in the settled order
// (bench/RESULTS.md, issue 24, sessions 12 and 13).
// Limit (measured, issue 24): a prefix layout cannot reach a static mesh's
// locality. A batch's new faces are mostly pairs around separate split edges
// and the older faces around a split are patched in place, so ACMR (cache 16)
// falls from 2.38 (refinement order) to about 1.8 on the bunny (1.6 with the
// windows), against 0.68 for the same triangles through meshoptimizer.
// Likewise fetch: each batch's run sweeps the whole surface once, so vertex
// fetch overfetch (meshopt, 128 KiB) stays about 4-5 against 1.1-1.2 for the
// static mesh (it was 10-11 with vertices in split order).
#include <cstddef>
#include <cstdint>
#include <vector>

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
    UninitVector<uint32_t> faces, order, number;
    // Frees the batch arrays (the reader: at the end of each feed).
    void release_batch_arrays() {
        for (auto* v : {&faces, &order, &number}) UninitVector<uint32_t>().swap(*v);
    }
};

// The draw order of `face_count` triangles (`indices`, three per face;
// `qpos`: 3 position codes per vertex, every vertex indexed): writes to order[i]
// the face drawn i-th (a permutation of 0 .. face_count-1), the faces sorted
// stably by the Morton code of their first corner (10 bits per axis).
void cache_order(const uint32_t* indices, size_t face_count, const uint16_t* qpos, uint32_t* order,
                 CacheOrderScratch& scratch);

// Numbers the vertices [first, first + count) in the order the faces
// order[0 .. face_count) (faces of `indices`, three corners each) first use
// them: number[k] is the new number of vertex first + k, a permutation of
// [first, first + count) (vertices those faces never use come last, in their
// order). The vertex fetch order of meshopt_optimizeVertexFetchRemap over the
// faces in that order, restricted to one batch's vertices, so a batch's
// renumbering leaves every other number alone.
void first_use_order(const uint32_t* indices, const uint32_t* order, size_t face_count, uint32_t first, uint32_t count,
                     uint32_t* number);

}  // namespace body::pm
