#pragma once
// Branching: one contour on a slice corresponding to several on the next.
//
// The default method keeps the surface a closed 2-manifold: the single contour
// is partitioned among the branches (each vertex goes to the nearest branch).
// The largest branch is the main one; every other branch keeps one arc, which
// is cut off by a straight chord lifted to `chord_z` (between the two slices);
// the main piece is what remains, with each cut-off arc replaced by its chord.
// Each piece is then tiled with its branch; a side piece and the main piece
// share their chord edges in opposite directions, so the bands glue into one
// surface. Cutting off local caps (instead of meeting at a common centre) keeps
// each band near its branch.
// Any contour of 3 or more vertices splits among any number of branches: the
// main branch always keeps a vertex, a side branch nearest no vertex takes the
// main vertices nearest it, and when the contour has too few vertices for all
// branches the rest bud off a chord (a new vertex at `chord_z` on a chord edge
// of the main piece; the bud's piece is that triangle). Vertices the partition
// adds never lie, seen from above, on a segment from their contour neighbour to
// a branch vertex, so tiling a piece with its branch makes no flat triangle.
// The thesis method (`Overlap`) tiles every linked pair independently and
// leaves overlapping open bands; it is kept for comparison only.
// The partition is one of several constructions for a branch; which one a
// group gets, and in what order they are tried: branch_cascade.h.
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
// pieces, traversed in opposite directions. Errors only for fewer than two
// branches or a contour or branch of fewer than 3 vertices.
Result<std::vector<std::vector<uint32_t>>> partition_contour(std::span<const uint32_t> single,
                                                             std::span<const std::span<const Vec2>> branches,
                                                             double chord_z, std::vector<Vec3>& positions);

}  // namespace body
