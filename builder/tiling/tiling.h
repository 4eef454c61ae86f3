#pragma once
// Tiling: stitching two closed contours into a triangle band.
//
// Contract (shared by every tiling method):
// - `lower` and `upper` are closed polygons (last point not repeated) of at
//   least 3 points each, in 3-D (usually each planar at its own z, but branch
//   partitions and mid-slice contours may be anywhere between).
// - Both polygons have the same orientation as seen from +z. The caller picks
//   it: counter-clockwise for an outer wall, clockwise for a hole, so that the
//   band's triangles face away from the solid's interior.
// - Output: `triangles` receives (lower.size() + upper.size()) triangles as
//   index triples; ids [0, lower.size()) name lower's points and
//   [lower.size(), lower.size() + upper.size()) name upper's points. Every
//   contour edge (i, i+1 mod n) of both polygons is used by exactly one
//   triangle, traversed in the direction that makes the band consistently
//   oriented with normals facing outward for counter-clockwise input.
// - The band does not fold: the cost charges corners where the band turns back
//   on itself (folds before area), and a band whose triangles still cross each
//   other is repaired by diagonal flips that remove the crossings. A pair the
//   flips cannot untangle (jagged contours where no nearby tiling is free of
//   crossings) keeps the fewest crossings they reach.
// - No allocation beyond `triangles` and internal scratch proportional to the
//   input.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

enum class TilingMethod {
    Optimal,   // Fuchs-Kedem-Uselton minimum-area tiling with divide-and-conquer
    Multires,  // Meyers-style: coarse optimal tiling, detail added back with local swaps
};

const char* tiling_method_name(TilingMethod method);

Status tile_band(std::span<const Vec3> lower, std::span<const Vec3> upper, TilingMethod method,
                 std::vector<uint32_t>& triangles);

}  // namespace body
