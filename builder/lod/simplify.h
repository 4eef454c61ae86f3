#pragma once
// Progressive-mesh construction: quadric-error edge collapses (Garland & Heckbert
// 1997) recorded as vertex splits (Hoppe 1996). The .bpm writer: bpm_writer.h.
//
// Placement (Garland-Heckbert "optimal placement with a safe fallback"): an edge
// u -> v between two interior vertices puts the merged vertex v at the minimiser
// of Q_u + Q_v when that 3x3 system is well conditioned and the point lies near
// the edge; otherwise at the best (least quadric cost) of u's position, v's
// position and the midpoint. A placement that would flip or fold a face of either
// fan falls back to the half-edge collapse (v keeps its position), which is the
// only placement for boundary or non-manifold ends. So a split may move its parent
// back: each split records the parent's position before and after it, and a level
// is "a prefix of the vertex array + a prefix of the face array + index patches +
// the positions of the parents moved so far".
//
// Ordering: an indexed heap of vertices keyed by their cheapest outgoing collapse
// (the ordering quadric's cost per unit of its weight -- an area-weighted mean squared
// distance -- then the input vertex number). The ordering quadrics are rebuilt once from
// the current faces when the lossless phase ends (the cheapest collapse would move the
// surface by more than 1e-6 of the bounding-box diagonal) if it removed at least a
// quarter of the faces, so that a mesh with redundant flat detail (a linearly subdivided
// one) is simplified as its coarse original would be; the stored errors come from
// unit-weight quadrics accumulated from the input all along.
// The lossless phase of a large mesh (LodOptions::region_faces) runs first in regions,
// compact runs of the vertices' Morton order, each on its own heap and thread with a
// band two edges wide around the cuts frozen; the band and what is left go on in the
// global order. The result does not depend on the number of threads.
// Deterministic (no hash iteration, IEEE double arithmetic with contraction disabled
// in this library) and independent of the internal renumbering done for cache locality.
//
// Rejected collapses: triangle flips and folds (a normal turning by more than 78 degrees),
// near-degenerate results (also on the .bpm's 16-bit grid: no face whose codes are
// collinear), link-condition violations (would make the surface non-manifold),
// interior-to-boundary pulls, and anything that would reduce a closed component below a
// tetrahedron or an open one below one triangle.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"
#include "shared/mesh.h"
#include "shared/pm/large_array.h"

namespace body::lod {

struct LodOptions {
    size_t min_triangles = 0;         // stop collapsing at this many triangles (0: as far as topology allows)
    double boundary_weight = 100.0;   // weight of the boundary-preserving plane quadrics (x edge length^2)
    size_t chunk_splits = 4096;       // vertex splits per SPLT section (streaming granularity)
    bool normals = true;              // store octahedral normals (from the mesh, else area-weighted)
    bool optimal_placement = true;    // false: half-edge collapses only (the parent never moves)
    bool batch_rounds = true;         // splits in rounds inside each batch (split_order.h); false: by error
    bool coarse_intermediate = true;  // positions a later split moves on coarser grids (FORMAT.md v6); false: exact
    // The lossless phase of a large mesh runs in regions of about this many faces, in
    // parallel (at most 8 regions; none under twice this many faces). Changes the output.
    size_t region_faces = size_t(1) << 18;
    // Threads for those regions, and (2 or more) for the setup: the adjacency beside the
    // collapse loop's arrays, the quadrics in two halves (0: one per hardware thread).
    // The output is the same for any number.
    unsigned threads = 0;
    // Called now and then from the collapse loop of each mesh (not the threaded
    // lossless regions) with the faces removed so far and the faces it will try to
    // remove, once more at its end; e.g. a terminal's progress bar.
    std::function<void(size_t done, size_t total)> progress;
};

// A progressive mesh in refinement order, in the builder's precision.
// Vertex v < base_vertices belongs to the base mesh; split j adds vertex
// base_vertices + j as a child of splits[j].parent.
struct VertexSplit {
    uint32_t parent = 0;
    uint32_t face_count = 0;  // faces this split adds (1 on a boundary edge, else 2)
    double error = 0.0;       // object-space error of the level before this split (non-increasing in j)
    Vec3 parent_from{0.0};    // the parent's position at the level before this split
    Vec3 parent_to{0.0};      // ... and after it (equal for a half-edge collapse)
};

// (Prefaulted storage, every page written: see shared/pm/large_array.h.)
struct ProgressiveBuild {
    pm::PrefaultedVector<Vec3> positions;    // all vertices in PM order, each where it appears (base: coarsest)
    pm::PrefaultedVector<Vec3> normals;      // one per vertex
    pm::PrefaultedVector<uint32_t> indices;  // all faces in PM order, as they are when each face appears
    size_t base_vertices = 0, base_faces = 0;
    pm::PrefaultedVector<VertexSplit> splits;
    // Faces whose corner at the parent moves to the child when split j is applied:
    // patch_faces[patch_begin[j] .. patch_begin[j + 1]).
    pm::PrefaultedVector<uint32_t> patch_begin;
    pm::PrefaultedVector<uint32_t> patch_faces;
};

// Simplifies `mesh` as far as options allow and returns the refinement sequence.
// Unreferenced vertices and degenerate triangles of the input are dropped.
Result<ProgressiveBuild> build_progressive_mesh(const Mesh& mesh, const LodOptions& options = {});

// The mesh at level `level` (0 = base, splits.size() = full), in PM vertex order.
Mesh extract_level(const ProgressiveBuild& pm, size_t level);

}  // namespace body::lod
