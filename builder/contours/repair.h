#pragma once
// The repairs validate_contour_stack applies (validate.h), one contour or one
// cluster of crossing contours at a time. Points are in stack units.
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

// Removes consecutive equal points (cyclically); returns how many.
size_t remove_duplicate_points(std::vector<Vec2>& points);

// One kind of point removal on one contour: how many, where first, how far the
// boundary moved at most.
struct PointRepair {
    size_t count = 0;
    Vec2 at{0.0};
    double moved = 0.0;
    void note(const Vec2& p, double distance) {
        if (count++ == 0) at = p;
        moved = std::max(moved, distance);
    }
};
struct CleanupResult {
    PointRepair near_duplicate, collinear, spike;
};

// Removes, until none is left: points within `noise` of their predecessor
// (near duplicates), points within `noise` of the segment between their
// neighbours (collinear), and tips of zero-width spikes (a point whose
// neighbours lie on one side of it along one line, within `noise`).
CleanupResult clean_contour(std::vector<Vec2>& points, double noise);

// The union of the regions bounded by `loops` under the non-zero winding rule
// (Clipper, strictly simple output: no self-touching), as closed loops. Input
// points reappear bit for bit; crossing points are new. Output loops whose every
// point lies within `tolerance` of the other output loops' boundary (or, alone,
// whose extent is within it) are dropped; `moved` is the largest such distance
// and, for one input loop, also the largest distance from an input point the
// union swallowed (inside a curl) to the result's boundary.
struct RegionUnion {
    std::vector<std::vector<Vec2>> loops;
    size_t dropped = 0;
    double moved = 0.0;
    bool ok = true;  // false when Clipper refused the coordinates (out of its range)
};
RegionUnion union_regions(std::span<const std::vector<Vec2>> loops, double tolerance);

}  // namespace body

namespace body {

// Moves every vertex of `loop` that lies exactly at `point` by up to `step`
// into the loop's own region (along the bisector of its edges, at most a
// quarter of the shorter edge), so two loops that touch there come apart.
// Returns how far the vertices moved (0 if none lies at `point`).
double pull_inward(std::vector<Vec2>& loop, const Vec2& point, double step);

}  // namespace body
