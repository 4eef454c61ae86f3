#pragma once
// Union-ring branching: a ring at mid-slice around the union of a group's
// regions (both slices) takes the group's loops below and above, each side as
// a nested region (nested_region.h). The branch geometry stays inside the slab
// and within a few grid cells of the union of the two slices' regions.
#include <cstdint>
#include <span>
#include <vector>

#include "builder/branching/structure_surface.h"

namespace body {

// Boundary of the union of `loops` (xy), grown by one to two cells of a grid
// of spacing `cell` and with its holes filled: a simple counter-clockwise ring
// holding every loop strictly inside (at least half a cell away). Marching
// squares over the cell centres of the grown, hole-free, saddle-free mask; runs
// of collinear steps are merged. Empty when the union is not one piece. The
// cell grows when the grid would exceed about 4 million cells.
std::vector<Vec2> union_ring(std::span<const std::span<const Vec2>> loops, double cell);

// The union-ring construction for the group `gl` (slice s) and `gu` (slice
// s+1); short walls at the ring (a tenth of the half spacing). An input error
// with nothing useful built when no ring holds every loop.
Status connect_union_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                          std::span<const uint32_t> gu, bool hole);

}  // namespace body
