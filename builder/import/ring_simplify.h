#pragma once
// Topology-preserving simplification of the rings of one structure on one
// slice (Douglas-Peucker per ring, then a validity check over all rings).
//
// Contract:
// - `rings` are closed polygons (last point not repeated) that neither touch
//   nor cross each other or themselves, in pixel units. Marching squares output
//   qualifies; the mask tracer's coordinates are half-integers, which makes
//   every orientation test below exact (the field tracer's are not: its tests
//   are exact in double precision only up to rounding, and a ring misjudged
//   there is left for the contour validation's repairs).
// - Each ring is replaced by a subset of its own vertices (in order) such that
//   every dropped vertex lies within `tolerance` (pixel units) of the kept
//   polyline. The result again has no touching or crossing segments, keeps
//   each ring's orientation and the nesting of rings (which ring contains
//   which), and every ring keeps at least min(its size, 8) vertices (small
//   rings are simplified with a smaller tolerance, or not at all). Rings where the
//   simplified form would violate that are retried with half the tolerance,
//   then left unsimplified.
// - tolerance <= 0 leaves the rings unchanged.
#include <vector>

#include "shared/geometry.h"

namespace body {

void simplify_rings(std::vector<std::vector<Vec2>>& rings, double tolerance);

// True when no two segments of `rings` touch or cross (adjacent segments of a
// ring may share their common vertex but not fold back onto each other).
// Exposed for tests.
bool rings_are_simple(const std::vector<std::vector<Vec2>>& rings);

}  // namespace body
