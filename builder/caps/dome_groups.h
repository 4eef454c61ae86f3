#pragma once
// The dome's apexes: the dome is a height field sampled at one apex per group
// of adjacent flat-cap triangles, each group becoming a fan around its apex.
//
// A cap of up to kDomeSamples triangles gets one group per triangle (its
// centroid is the apex: 3 triangles for each flat one). A larger cap's boundary
// is sampled far more finely than the dome's shape needs, and one apex per
// triangle made its mesh 4x the flat cap's; there, runs of consecutive
// triangles (in the triangulator's order) that share an edge are merged into
// groups of up to min(16, ceil(F / kDomeSamples)) triangles, while their union
// stays a simple polygon star-shaped around its area centroid (every fan
// triangle strictly counter-clockwise). A group of k triangles gives k + 2
// triangles instead of 3k.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

constexpr size_t kDomeSamples = 4096;

struct DomeGroup {
    Vec2 apex;
    uint32_t first, count;  // its boundary, counter-clockwise: cycles[first .. first + count)
};

// `triangles` index `at` and are counter-clockwise. Fills `groups` and
// `cycles` (cleared first).
void dome_groups(std::span<const Vec2> at, std::span<const uint32_t> triangles, std::vector<DomeGroup>& groups,
                 std::vector<uint32_t>& cycles);

// The lifted groups: each group a fan around its apex, lifted by `lift` (the
// 3-D point of an apex) and appended to `positions`; `ids[i]` is the mesh
// vertex of the region's i-th point. `emit` receives each triangle
// counter-clockwise seen from +z. With `piece` = 0 chords between groups stay
// on the boundary's height (splitting them always was tried: it broke the AAL
// smoothing and bunny LOD tests, bench/RESULTS.md). With `piece` > 0 (`at`:
// the region's points, as `cycles` index them) each chord, a cycle edge that
// another group's cycle runs the other way, is split into the fewest equal
// pieces, at least 2 and at most kMaxChordPieces, no longer than `piece` in the plane, at
// lifted points shared by both groups; cycle edges on the region's boundary
// (traced contour edges) stay whole. The points lie on the chord in the plane,
// so the cap stays a height field over the region and cannot fold.
constexpr uint32_t kMaxChordPieces = 16;
void lift_groups(std::span<const DomeGroup> groups, std::span<const uint32_t> cycles, std::span<const uint32_t> ids,
                 const std::function<Vec3(const Vec2&)>& lift, std::vector<Vec3>& positions,
                 const std::function<void(uint32_t, uint32_t, uint32_t)>& emit, std::span<const Vec2> at = {},
                 double piece = 0.0);

}  // namespace body
