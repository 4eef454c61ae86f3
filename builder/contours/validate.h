#pragma once
// Validation and repair of a contour stack before meshing.
//
// Checks, in order, per contour (units are the stack's; tolerances relative to
// the contour's own extent):
//   - every coordinate finite                          -> error
//   - consecutive duplicate points (also last == first) -> removed, warning
//   - fewer than 3 distinct points                     -> error
//   - keyhole: a vertex visited twice (a hole joined to its outer boundary by a
//     zero-width cut, as RT-STRUCT writes them)          -> split into loops, warning
//   - zero area                                        -> error
//   - self-intersection, or two contours of the same structure (unlabelled
//     contours count as one group) touching or crossing on one slice
//                                                      -> error with the crossing point
// Error messages name `path`, the slice and contour indices of the input file
// (Contour::source_slice / source_contour) and the reason.
//
// Nesting: within a group of contours on one slice, a contour's depth is the
// number of other contours containing it (even-odd rule): even = solid boundary
// (outer wall, island), odd = hole.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "shared/error.h"

namespace body {

// Validates and repairs `stack` in place; appends human-readable warnings.
Status validate_contour_stack(ContourStack& stack, const std::string& path, std::vector<std::string>& warnings);

// Splits a closed polygon at vertices visited twice (keyhole cuts). Loops of
// fewer than 3 points or zero area (the cut itself) are dropped. A polygon
// without repeated vertices comes back as the only element.
std::vector<std::vector<Vec2>> split_keyholes(std::span<const Vec2> points);

// Even-odd containment among `contours` (simple, pairwise disjoint boundaries).
// `parent[i]` is the innermost contour containing i or -1; `depth[i]` counts
// the contours containing i.
struct Nesting {
    std::vector<int> parent;
    std::vector<int> depth;
};
Nesting compute_nesting(std::span<const std::span<const Vec2>> contours);
// The same among the contours `members` (indices) of `slice`.
Nesting compute_nesting(const Slice& slice, std::span<const uint32_t> members);

// Point-in-polygon (even-odd). Points on the boundary may go either way.
bool point_in_polygon(const Vec2& p, std::span<const Vec2> polygon);

// First crossing or touching between non-adjacent edges of the given loops, if
// any: loop indices a <= b and the point.
struct Crossing {
    bool found = false;
    size_t loop_a = 0, loop_b = 0;
    Vec2 point{0.0};
};
Crossing find_crossing(std::span<const std::span<const Vec2>> loops);

}  // namespace body
