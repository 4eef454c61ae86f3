#pragma once
// Validation and repair of a contour stack before meshing: the one code path
// of `bodygen check`, `bodygen build` and the importers (`bodygen contours`).
//
// Per contour, in order (tolerances: see RepairOptions):
//   - every coordinate finite                            -> error
//   - consecutive duplicate points (also last == first)   -> removed
//   - near-duplicate points (closer than the point noise) -> removed       (repair mode)
//   - collinear points (on the line of their neighbours)  -> removed       (repair mode)
//   - zero-width spikes (the contour folds back on itself) -> tip removed  (repair mode)
//   - fewer than 3 distinct points, or zero area          -> error; in repair mode a contour no
//                                                             larger than the tolerance is dropped
//   - keyhole: a vertex visited twice (a hole joined to its outer boundary by a
//     zero-width cut, as RT-STRUCT writes them)            -> split into loops
// Per slice and structure (unlabelled contours count as one group):
//   - self-intersections and contours touching or crossing -> error in strict mode; otherwise
//     each cluster of crossing contours is replaced by the union of its regions (Clipper,
//     non-zero fill, contours oriented by their nesting depth), so figure-eights split into
//     their lobes, curls merge and overlapping contours of one structure are unioned; pieces
//     of the result whose every point lies within the tolerance of the rest (the slivers of
//     zig-zags) are dropped. A repair that would move a point further is refused.
//   - contours smaller than RepairOptions::min_area       -> dropped with a warning
//   - contours of different structures that cross (touching is normal: label maps) -> one
//     warning per pair of structures (first place, number of slices), both kept.
// Each repair is one line "PATH: slice S contour C: at (x, y): what, points moved up to D"
// naming the input file's slice and contour (Contour::source_slice / source_contour).
//
// Nesting: within a group of contours on one slice, a contour's depth is the
// number of other contours containing it (even-odd rule): even = solid boundary
// (outer wall, island), odd = hole.
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "shared/error.h"

namespace body {

// Default repair tolerance as a fraction of the stack's extent (the diagonal of
// all its points' x-y bounding box); chosen by measurement (bench/RESULTS.md, issue 23).
inline constexpr double kDefaultRepairTolerance = 1e-3;

struct RepairOptions {
    // Refuse (exit 2) on the first problem that is not a duplicate point or a keyhole,
    // as before repairs existed.
    bool strict = false;
    // Largest distance a repair may move a point, in stack units; <= 0 means
    // kDefaultRepairTolerance times the stack's extent.
    double tolerance = 0.0;
    // Contours (solid or hole) with a smaller area, in stack units squared, are
    // dropped after the repairs with a warning ("small"); 0 keeps every contour.
    // A speck traced beside a structure would otherwise become a floating blob.
    double min_area = 0.0;
};

// What validation did: one line per repair or warning, and repairs counted by
// kind ("duplicate", "near_duplicate", "collinear", "spike", "degenerate",
// "keyhole", "self_intersection", "overlap", "small"; "structure_overlap" counts warnings).
struct RepairLog {
    std::vector<std::string> lines;
    std::map<std::string, size_t> counts;
    void add(const std::string& kind, std::string line) {
        ++counts[kind];
        lines.push_back(std::move(line));
    }
};

// Validates and repairs `stack` in place.
Status validate_contour_stack(ContourStack& stack, const std::string& path, const RepairOptions& options,
                              RepairLog& log);
// The same with default options; appends the log's lines to `warnings`.
Status validate_contour_stack(ContourStack& stack, const std::string& path, std::vector<std::string>& warnings);

// The tolerance `options` resolves to for `stack`.
double repair_tolerance(const ContourStack& stack, const RepairOptions& options);

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

// A crossing or touching between non-adjacent edges of the given loops (or
// adjacent edges folding back): loop indices a <= b and the point.
struct Crossing {
    bool found = false;
    size_t loop_a = 0, loop_b = 0;
    Vec2 point{0.0};
    bool crosses = false;  // some pair of edges crosses (not only touches or overlaps along a line)
};
// Every pair of loops (a <= b) that meets, once, with the lowest such point
// (by x, then y); sorted by (a, b). Segments are found through a bounding-box
// tree: O(n log n) for n edges plus the pairs whose boxes overlap.
std::vector<Crossing> find_crossings(std::span<const std::span<const Vec2>> loops);
// The first of find_crossings, or found == false.
Crossing find_crossing(std::span<const std::span<const Vec2>> loops);

}  // namespace body
