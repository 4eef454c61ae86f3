#pragma once
// The branching cascade: how a group of linked loops that is not 1:1 is
// joined. Constructions are tried in order of faithfulness:
//   1. nested region (nested_region.h), when the branches lie inside the
//      single loop;
//   2. partition keeping every branch (partition_bands.h);
//   3. union ring (union_ring.h);
//   4. partition with interior side branches detached;
//   5. hull ring (hull_ring.h).
// 1, 2 and 4 need a single loop on one side; N:M starts at 3. The first whose
// triangles do not cross each other is kept; failing that, the first that
// could be built at all (still closed, but crossing).
#include <cstdint>
#include <span>

#include "builder/branching/structure_surface.h"

namespace body {

// Joins the loops `gl` (slice s) and `gu` (slice s+1), sorted indices into the
// slices' loops, not both single, all solid or all holes (`hole`). On failure
// returns the first construction's error (or "branching failed" naming the
// first lower loop) and leaves the surface as it was.
Status connect_branches(StructureSurface& surface, size_t s, std::span<const uint32_t> gl, std::span<const uint32_t> gu,
                        bool hole);

}  // namespace body
