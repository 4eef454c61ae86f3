#pragma once
// Shape-based intermediate slices: where a band between two slices cannot
// follow the surface because the structure's topology changes between them.
//
// A band (tiling) joins contours of the two slices directly, so a hole that
// exists only between the slices (a tilted torus cut near its equator: two C
// shapes opening to opposite sides, the ring closed only in between) is swept
// over by the band. Shape-based interpolation (the zero set of the mean of
// the two slices' signed distance fields) sees the hole. When that mid-height
// section has the same number of solids as both slices but a number of holes
// that neither slice has, the band changes genus inside the gap: the mid-height
// section is returned as a slice to insert, so that each half-band joins
// contours of one topology to the next by the existing hole and branching
// constructions.
//
// Contract:
// - `lower`, `upper`: one structure's contours on two adjacent slices, simple
//   closed polygons of any orientation that do not cross; inside is even-odd
//   over each slice's contours (solids and the holes nested in them).
// - The decision uses the two slices rasterised at kShapeDetectCells cells
//   along the longer side of their joint box, signed distances by a Euclidean
//   transform of the cells, and counts of 4-connected solid and 8-connected
//   hole regions (holes: outside regions not reaching the raster's border):
//   a slice is inserted when the mean field's section has solids and its
//   (solids, holes) differ from both slices' (a genus or branch change that
//   happens only between them: a band from either end cannot produce it).
// - When inserted, the contours are the mean field's zero set traced by
//   marching squares (slicing/marching_squares.h) on a raster of
//   kShapeTraceCells cells along the longer side, the same transform's
//   distances (within 0.71 of a cell of the exact ones): closed, simple, not
//   crossing each other, with the inside on the left, cleaned of points
//   within 0.01 cell of their neighbours' segment (contours/repair.h); rings
//   under 2 square cells are dropped. Empty when not needed.
// - Limit: a section with a hole that neither slice has (C shapes whose
//   openings are narrower than the wall) is inserted too, but the pipeline's
//   hole constructions do not yet join that hole to the C shapes' notches
//   (branching/open_holes.h needs a quarter of its vertices outside them): it
//   is closed by caps, about as far from the surface as the band was. Where
//   such caps close a piece of the mesh that meets no input contour (a
//   cavity), the pipeline removes the piece (build_pipeline.cpp).
// - At branches (`at_branches`, the interpolated build), a section is also
//   inserted where the band or branch construction would decide the shape
//   between the slices alone, judged on a raster of kShapeBranchCells cells:
//   (a) the two slices' solids that meet the other slice's region (grown by
//   one cell; a speck under a cell by a cell holding one of its points) differ
//   in number (a branch: one contour meets several), at height fraction 0.5;
//   solids over nothing are ends that the caps close and do not count;
//   (b) else the first of the blended fields' sections at fractions 0.5,
//   0.25, 0.75 whose number of 4-connected solids differs from both slices'
//   (a piece of its own between them: a toe that joins its body's contour
//   only on the upper slice), at that fraction. The section at fraction t is
//   the zero set of (1 - t) lower + t upper signed distance, traced as above.
// - Cost: O(R + E * rows) for R raster cells and E edges, twice when inserted;
//   at branches a few more rasters of kShapeBranchCells (and one per solid
//   whose points miss the other region).
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

inline constexpr int kShapeDetectCells = 32;
inline constexpr int kShapeTraceCells = 256;
inline constexpr int kShapeBranchCells = 64;

// A section to insert: its contours (empty when none) at height fraction t
// of the gap from `lower` (0) to `upper` (1).
struct ShapeSlice {
    double t = 0.5;
    std::vector<std::vector<Vec2>> rings;
    bool at_branch = false;  // inserted for a branch or a piece of its own, not a topology change
};
ShapeSlice shape_slice_between(std::span<const std::span<const Vec2>> lower,
                               std::span<const std::span<const Vec2>> upper, bool at_branches);

// The topology-change section alone (at_branches false), at fraction 0.5.

std::vector<std::vector<Vec2>> shape_mid_slice(std::span<const std::span<const Vec2>> lower,
                                               std::span<const std::span<const Vec2>> upper);

}  // namespace body
