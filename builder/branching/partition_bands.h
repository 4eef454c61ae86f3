#pragma once
// Partition branching on the structure's surface: the single loop is split
// among its branches (partition_contour, branching.h) and each piece is tiled
// with its branch, so the bands share their chord edges and glue into one
// closed surface.
#include <cstdint>
#include <span>
#include <vector>

#include "builder/branching/structure_surface.h"

namespace body {

// Splits the id loop `single` among `branch_ids` (loops of `others`, the
// other slice) with chords at `chord_z`, then tiles each piece with its
// branch; `single_is_lower` says which side of the bands it is. Errors name
// `blame`'s contour. With `blend_low` >= 0 the chords leave `chord_z` for the
// heights of chord_heights.h, at least `blend_low` of the gap from the single
// loop's slice and kBlendLow from the other.
Status split_into_bands(StructureSurface& surface, std::span<const uint32_t> single, const std::vector<Loop>& others,
                        std::span<const uint32_t> branch_ids, double chord_z, bool single_is_lower, const Loop& blame,
                        double blend_low = -1);
inline constexpr double kBlendLow = 0.05;

// A group between slices s and s+1 with one single loop on one side: the
// partition, chords at their blended heights, at mid-slice when those cross
// what was built. With `detach`, side branches lying wholly
// inside the single loop are detached first (unlinked and marked for flat
// caps, closed at their own slice) so that they do not pull a far-away arc of
// it across the others; the largest branch is never detached.
Status connect_partition(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                         std::span<const uint32_t> gu, bool detach);

}  // namespace body
