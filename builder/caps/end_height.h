#pragma once
// How far past its last slice a structure (or a hole) goes on: the height of
// the end cap's dome, from the slope of the surface the bands already built.
//
// The ending loop's cross-section area is extrapolated past the slice from
// the loops its bands come from: each vertex's band neighbours on the other
// side (their mean: the tiling's rung partners) make a ring one slice back,
// their partners one two slices back, the same points the interpolation's
// parabolic end slope uses. A quadratic through the three areas (linear with
// only two slices) falls to zero where the solid ends: exactly at a sphere's
// or a cone's tip, and near it on any smooth (elliptic) tip, whose
// cross-section area is about linear in the distance to the tip. The cap's
// dome takes that height, limited to `limit` (the pipeline's: just under half the gap to the
// next slice: nothing was traced there, so the tip lies within one gap, and
// about half is the least bad guess when the slope says nothing, as 3D
// Slicer's planar-contour route does).
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

// Per vertex: the sums and counts of its triangle neighbours strictly below
// and strictly above it in z. `triangles` index `positions`.
// The second level (`below2`, `above2`): sums of those neighbours' own means
// on the same side, one slice further.
struct RungPartners {
    std::vector<Vec3> below, above, below2, above2;
    std::vector<uint32_t> below_n, above_n, below2_n, above2_n;
};
void rung_partners(std::span<const Vec3> positions, std::span<const uint32_t> triangles, RungPartners& out);

struct EndHeight {
    double height = 0;     // in (0, limit]
    bool closing = false;  // the slope closes the loop within `limit` (else the limit is used)
};

// `xy` is the loop (any orientation), `ids` its vertices (all at one z).
// `up`: the structure ends upwards (the partners are below). `limit` > 0.
EndHeight end_height(std::span<const Vec2> xy, std::span<const uint32_t> ids, std::span<const Vec3> positions,
                     const RungPartners& partners, bool up, double limit);

}  // namespace body
