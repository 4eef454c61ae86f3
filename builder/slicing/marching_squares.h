#pragma once
// Marching squares on a binary mask: the boundary of the inside region as
// closed polygons with vertices on the half-voxel boundary.
//
// Contract:
// - `mask` holds width * height bytes, row-major (x fastest); nonzero = inside.
//   Pixels outside the mask are outside.
// - Coordinates: pixel (x, y) has its centre at (x, y). Every vertex is the
//   midpoint between an inside pixel centre and a 4-neighbour outside pixel
//   centre, so vertices lie on the voxel faces (half-integer in one axis,
//   integer in the other): the boundary runs on the half-voxel boundary and
//   cuts each convex voxel corner by a 1/8-voxel triangle.
// - Rings are closed (last point not repeated), collinear vertices removed,
//   inside on the left: outer boundaries counter-clockwise (positive area),
//   holes clockwise.
// - Diagonal connections: the inside is 4-connected (pixels touching only at
//   a corner are separate regions, each with its own ring), the outside
//   8-connected. Applied to every label of a label map this gives regions with
//   disjoint interiors, and rings of one mask never touch or cross: the two
//   segments of a saddle cell are sqrt(2)/2 voxel apart.
// - `rings` is cleared first; scratch is proportional to the mask.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

void trace_mask_boundaries(std::span<const uint8_t> mask, size_t width, size_t height,
                           std::vector<std::vector<Vec2>>& rings);

// Marching squares on a scalar field: the boundary of {value > level} as
// closed polygons, each vertex where linear interpolation along a cell edge
// between two pixel centres reaches `level`.
//
// Contract:
// - `field` holds width * height values, row-major; pixels outside the grid
//   have value 0, and level > 0 (an indicator smoothed, traced at 0.5).
// - Same coordinates, orientation (inside on the left), closure and dropping
//   of exactly collinear vertices as trace_mask_boundaries.
// - Saddle cells (inside corners diagonal): the two inside corners are joined
//   through the cell when the mean of its four values is above `level`, else
//   cut apart; one rule for every cell, so each cell edge is crossed at most
//   once and the rings of one field never touch or cross. Fields whose values
//   sum to at most 1 (smoothed indicators of disjoint labels) never join the
//   same cell for two labels.
// - Crossings are kept 1/128 pixel off the pixel centres, so no two vertices
//   coincide where a value equals the level.
// - On a 0/1 field with level 0.5 the result equals trace_mask_boundaries of
//   the same mask, point for point.
// - `rings` is cleared first; scratch is proportional to the field.
void trace_field_isolines(std::span<const float> field, size_t width, size_t height, float level,
                          std::vector<std::vector<Vec2>>& rings);

}  // namespace body
