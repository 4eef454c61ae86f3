#pragma once
// Surface fairing for meshes built from traced or voxel contours: removes the
// terraces that slice spacing and voxel staircases leave, with far less shrinking
// than a plain Laplacian flow (which pulls the structure towards its centre).
//
// Taubin's lambda|mu filter: each iteration moves every vertex by lambda x its
// umbrella vector (the mean of its edge neighbours minus itself), then by mu
// (negative) x the new umbrella vector. With lambda = 0.5 and the pass-band
// frequency k = 0.1 (1/lambda + 1/mu = k), detail above the pass band (stair
// steps, slice terraces) decays and a large shape keeps its volume to within a
// few per cent; small thin ones lose more. Connectivity is unchanged: a
// closed 2-manifold stays one. Vertices on a boundary edge (an edge with one face)
// keep their positions, so open meshes keep their rims. Vertices move off their
// slice planes: the pipeline's guarantee that re-slicing at an input plane gives
// back its contour no longer holds exactly.
#include <cstddef>
#include <cstdint>
#include <span>

#include "shared/geometry.h"

namespace body {

struct FairingOptions {
    int iterations = 0;      // lambda|mu pairs; 0 leaves the mesh as it is
    double lambda = 0.5;     // smoothing step, in (0, 1)
    double pass_band = 0.1;  // k_PB in (0, 1/lambda): mu = 1 / (k_PB - 1/lambda)
};

// Smooths `positions` in place. `indices`: 3 per triangle, each < positions.size().
// Smoothing adds no self-intersection: the vertices of any triangle pair that
// would intersect after it and did not before are left where they were (the
// return value counts them; 0 when nothing had to be put back).
// Allocates its working memory (the edge list, two copies of the positions, the
// intersection test's grid) and frees it before returning.
size_t taubin_smooth(std::span<Vec3> positions, std::span<const uint32_t> indices, const FairingOptions& options);

}  // namespace body
