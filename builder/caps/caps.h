#pragma once
// Caps: closing a structure where it ends (nothing linked above or below).
//
// A cap covers a planar region given as loops on one slice: loops[0] is the
// outer boundary, the others are holes inside it. Loops are closed (last
// point not repeated), any orientation, simple and pairwise disjoint.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

enum class CapStyle {
    Flat,  // the region triangulated in its plane
    Dome,  // the region lifted to a dome about half a slice spacing high
    None,  // left open
};

const char* cap_style_name(CapStyle style);

// Triangulates a polygon with holes: up to 4096 points by ear clipping after
// bridging each hole to the outer boundary, above that by the O(n log n)
// monotone sweep (monotone_cap.h). Triangle ids index the loops concatenated in order
// (loops[0] first). Triangles are counter-clockwise seen from +z. No new
// vertices. Fails when the region cannot be triangulated without degenerate
// triangles (e.g. zero area).
Status triangulate_polygon_with_holes(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles);

// Builds a cap over a region at height `z`. `ids[k][i]` is the mesh vertex of
// loops[k][i]. Triangles face +z when `up`, -z otherwise. A dome adds vertices
// to `positions` at most |dome_height| away from the plane: on the side the cap
// faces when `dome_height` > 0 (a solid going on past its last slice), on the
// other side when < 0 (a hole whose void goes on past it: the cap faces into
// the void, the dome bulges into the solid). Triangles (global ids) are
// appended to `triangles`. The dome rises as sqrt(u), u the distance to the
// boundary over its largest value (steep at the rim: a wall that ends flat),
// or with `tip` as u (2 - u) (a paraboloid over a disc: an end whose
// cross-section shrinks linearly to a point, end_height.h). The dome's
// chords between fans stay at the slice's height unless `lift_chords`: then
// each is split at points on the dome at most half the region's largest
// boundary distance apart (dome_groups.h), so no flat chord across the region
// holds part of the cap at the slice (where a solid ends between slices,
// those chords were the farthest part of the mesh from the true surface,
// bench/RESULTS.md). Loop edges are never split.
Status build_cap(std::span<const std::span<const Vec2>> loops, std::span<const std::span<const uint32_t>> ids, double z,
                 bool up, CapStyle style, double dome_height, std::vector<Vec3>& positions,
                 std::vector<uint32_t>& triangles, bool tip = false, bool lift_chords = false);

}  // namespace body
