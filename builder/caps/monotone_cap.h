#pragma once
// Triangulation of a polygon with holes in O(n log n) time: monotone pieces
// from a plane sweep, each triangulated by a stack walk. The contract of the
// loops is caps.h's (loops[0] outer, the others holes, any orientation,
// simple and pairwise disjoint). Triangle ids index the loops concatenated in
// order; triangles are counter-clockwise seen from +z; no new vertices.
// Returns false (triangles appended so far are the caller's to drop) when the
// loops break the contract badly enough that the sweep finds no consistent
// pieces (crossing or touching loops); collinear points may leave flat
// triangles, which the caller flips away.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

bool triangulate_monotone(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles);

}  // namespace body
