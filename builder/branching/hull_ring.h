#pragma once
// Hull-ring branching, the last resort: a ring at mid-slice on the convex hull
// of a group's loops (both slices) takes the loops below and above. Without
// loops nested in the group's loops, the hull grown by 1% around its centre
// holds every loop strictly inside and each side is a nested region
// (nested_region.h); otherwise the hull is split among each side's loops by
// the partition (partition_bands.h), chords a quarter spacing from it.
#include <cstdint>
#include <span>
#include <vector>

#include "builder/branching/structure_surface.h"

namespace body {

// Convex hull of `points`, counter-clockwise, without collinear points
// (Andrew's monotone chain); fewer than 3 points come back sorted and unique.
std::vector<Vec2> convex_hull(std::vector<Vec2> points);

// The hull-ring construction for the group `gl` (slice s) and `gu` (slice s+1).
Status connect_hull_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                         std::span<const uint32_t> gu, bool hole);

}  // namespace body
