#pragma once
// Branching: one contour on a slice corresponding to several on the next.
//
// The default method keeps the surface a closed 2-manifold: the single contour
// is partitioned among the branches (each vertex goes to the nearest branch;
// runs are merged until every branch owns one arc), and the arcs are closed by
// chords that meet at a centre point, lifted to `chord_z` (between the two
// slices). Each piece is then tiled with its branch; neighbouring pieces share
// their chord edges in opposite directions, so the bands glue into one surface.
// The thesis method (`Overlap`) tiles every linked pair independently and
// leaves overlapping open bands; it is kept for comparison only.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

enum class BranchingMethod {
    Partition,  // nearest-branch partition of the single contour, closed manifold
    Overlap,    // thesis: independent pair tilings, overlapping (not manifold)
};

const char* branching_method_name(BranchingMethod method);

// `single` lists mesh vertex ids (into `positions`) of the single contour, in
// its orientation. `branches` are the other slice's contours (xy). On success,
// returns one closed id loop per branch (same orientation as `single`), made of
// an arc of `single` and chord vertices appended to `positions` at `chord_z`.
// Every edge of `single` lies in exactly one piece; every chord edge in two
// pieces, traversed in opposite directions.
Result<std::vector<std::vector<uint32_t>>> partition_contour(std::span<const uint32_t> single,
                                                             std::span<const std::span<const Vec2>> branches,
                                                             double chord_z, std::vector<Vec3>& positions);

}  // namespace body
