#pragma once
// Slicing a closed triangle mesh with parallel planes into a contour stack:
// the inverse of reconstruction, used to make test stacks from real meshes and
// to measure how faithfully a rebuilt mesh reproduces its input contours.
//
// Contract:
// - `positions`/`indices`: a closed, consistently oriented triangle mesh
//   (three indices per triangle, each < positions.size()).
// - `axis`: 0, 1 or 2 (x, y, z). The coordinates are permuted cyclically so
//   that the slicing axis becomes z: axis x maps (x, y, z) to contour points
//   (y, z) at height x; axis y maps to (z, x) at height y.
// - `planes`: heights along the axis, any order; each plane gives one slice
//   (planes closer than kSliceMergeTolerance merge, as on reading a stack).
// - A vertex exactly on a plane counts as above it (symbolic perturbation), so
//   every triangle crossing a plane yields one segment and segments chain into
//   closed loops through shared mesh edges. Loops are counter-clockwise seen
//   from +axis around solid (outer walls) and clockwise around holes, as the
//   mesh orientation dictates. Consecutive points closer than 1e-5 of the
//   mesh's bounding-box diagonal are merged (the first is kept); loops
//   with fewer than 3 points or zero area (a plane touching a vertex) are
//   dropped; slices without contours are left out.
// - Every contour gets `structure` (may be empty).
// - Errors (exit code 2): an index out of range, or a mesh open at a plane
//   (a chain that does not close), naming the plane index and height.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

Result<ContourStack> slice_mesh(std::span<const Vec3> positions, std::span<const uint32_t> indices, int axis,
                                std::span<const double> planes, const std::string& structure = {});

// Removes the planes that cross a triangle involved in a self-intersection of
// the mesh (their slices would hold crossing contours, which a contour stack
// rejects). Returns how many were removed.
size_t drop_planes_through_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                              int axis, std::vector<double>& planes);

// Moves each plane that crosses such a triangle just past the end (along the
// axis) of the span those triangles cover, to the nearer end, when that is
// within kPlaneMoveLimit of the gap to its nearer neighbour (so planes keep
// their order and no gap doubles); otherwise the plane is removed. `planes`
// comes back sorted. Returns how many moved, were removed, and the largest
// move as a fraction of the gap.
constexpr double kPlaneMoveLimit = 0.45;   // two neighbours moving towards each other stay 0.1 gap apart
constexpr double kPlaneMoveMargin = 1e-3;  // of the gap, past the span's end
struct PlaneMoves {
    size_t moved = 0, dropped = 0;
    double largest_move = 0;
};
PlaneMoves move_planes_off_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                              int axis, std::vector<double>& planes);

// `count` heights evenly spaced strictly inside (lo, hi): lo + (k + 0.5) (hi - lo) / count.
std::vector<double> evenly_spaced_planes(double lo, double hi, size_t count);

}  // namespace body
