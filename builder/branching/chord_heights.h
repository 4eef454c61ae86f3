#pragma once
// Chord heights by shape-based interpolation: a partition chord (branching.h)
// is where the surface between a single loop and its branches splits, so each
// chord vertex goes to the height where the linear blend of the two slices'
// distance fields is zero: at distance d_s from the single loop and d_b from
// the nearest branch, the fraction d_s / (d_s + d_b) of the gap from the single
// loop's slice. A chord then meets its ends on the single loop smoothly, dips
// towards the branches' slice where they lie far apart (a wide notch mouth, a
// deep crotch) and stays near the single loop where they nearly touch, instead
// of running flat at one height across the gap between them.
#include <cstddef>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

// Distance from `p` to the nearest edge of any of `loops` (closed polygons).
double loops_distance(const Vec2& p, std::span<const std::span<const Vec2>> loops);

// Sets the z of positions[first ..] (chord vertices whose xy lie between
// `single` at `z_single` and `branches` at `z_branch`) to the blend's zero,
// the fraction clamped to [lo, hi] of the gap from `z_single`.
void blend_chord_heights(std::vector<Vec3>& positions, size_t first, std::span<const Vec2> single, double z_single,
                         std::span<const std::span<const Vec2>> branches, double z_branch, double lo, double hi);

}  // namespace body
