#pragma once
// Smooth between-slice interpolation of a mesh built from a contour stack: the
// linear bands between adjacent slices are replaced by cubic (Hermite)
// curves through the band's corresponding points, with `rings` intermediate
// rings per slice gap. Every vertex of the input mesh keeps its position and
// every input edge lying in a slice plane stays an edge, so the traced
// contours stay exactly on the mesh.
//
// Contract:
// - `positions`/`indices` (3 per triangle, each < positions.size()) are the
//   mesh; `slice_z` the stack's slice heights in increasing order. A vertex is
//   on slice s when its z equals slice_z[s] exactly (the pipeline puts contour
//   vertices there); a band triangle has its three vertices on two adjacent
//   slices.
// - Each edge of a band triangle joining adjacent slices (a "rung": the
//   tiling's point correspondence) is split into `count` points (below) at the
//   heights z_s + k/(count+1) (z_{s+1} - z_s), placed on the cubic Hermite curve whose
//   end tangents are Catmull-Rom slopes at each end from the rung and the rung
//   continuing it past that end (of the end vertex's rungs on the other side,
//   the one whose direction is nearest; weighted for uneven spacing; parabolic
//   end slope at a structure's end), turned into the bands' tangent plane at
//   the vertex. A rung and its continuation meet with one tangent when each
//   continues the other. Rungs at a crease or corner (a band triangle there
//   turns more than 30 degrees from the vertex's mean band normal) stay
//   straight, so flat sides stay flat. A rung also used by a triangle that is not
//   a band triangle (branch walls, mid-slice rings) is split on its straight
//   line, and that triangle is re-triangulated in its own plane.
// - Point counts: with `tolerance` > 0 each split rung takes the fewest
//   points, at most `rings`, that keep the estimated distance between its
//   curve and the polyline through its points under `tolerance` x the slice
//   gap (none where the curve stays on its chord, or the rung stays straight);
//   every triangle on the rung reads its count. `least` > 0 (stack units)
//   raises that bound to max(`tolerance` x gap, `least`): a curve that leaves
//   its chord by less than the contours' own precision gets no points. Both
//   0: every split rung gets `rings`.
// - Band triangles become strips from their base to their apex with the
//   original orientation: the two rungs' points merged by height (quads where
//   the counts are equal, 2 x count + 1 triangles); the mesh's connectivity
//   class (closed, manifold, genus) is kept.
// - No new self-intersection: rungs whose curves make two triangles meet that
//   did not meet on the straight mesh are put back on their straight lines
//   until none is left (the return value counts them).
// - `rings` = 0 leaves the mesh as it is. Memory: O(output size).
// - `threads` > 1 runs the first round's search for meeting triangles on that
//   many threads (the result does not depend on it).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

struct InterpolationStats {
    size_t rungs = 0;         // band edges split
    size_t curved = 0;        // of these, on their Hermite curve
    size_t straightened = 0;  // put back on their straight line to avoid a self-intersection
    size_t points = 0;        // points added on the split rungs (rings x rungs without a tolerance)
};

InterpolationStats interpolate_between_slices(std::vector<Vec3>& positions, std::vector<uint32_t>& indices,
                                              std::span<const double> slice_z, int rings, double tolerance = 0.0,
                                              double least = 0.0, unsigned threads = 1);

}  // namespace body
