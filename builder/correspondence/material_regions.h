#pragma once
// Correspondence of nested contours by their material regions.
//
// A contour's region is the area it bounds minus its immediate children's (a
// solid's region is the material between it and its holes; a hole's is the void
// between it and the solids inside it). The regions of one slice are disjoint,
// so two concentric rings link to their own partners only, not to every ring
// whose outline contains them.
//
// Contract: each slice is its contours (simple closed polygons, any orientation,
// not crossing each other) with their nesting (`parent`: index of the innermost
// contour containing it, -1 for none; a contour at odd depth is a hole). The
// result links lower to upper contours of the same kind (solid with solid, hole
// with hole), as indices into the full lists, sorted, without duplicates.
// Overlap: linked when their regions overlap (area above 1e-9 of the smaller
// region). Ellipse: the thesis method on whole contours, per kind.
//
// Cost: O(E log E) for E edges plus the pairs of contours whose boundaries meet
// and, per such pair, the product of their child counts; no pass over all pairs
// of contours (a slice of thousands of nested rings stays near linear).
#include <span>
#include <vector>

#include "builder/correspondence/correspondence.h"

namespace body {

struct NestedContours {
    std::span<const PolygonSpan> contours;
    std::span<const int> parent;
};

std::vector<ContourLink> correspond_nested(NestedContours lower, NestedContours upper, CorrespondenceMethod method);

// Region overlap areas of the linked pairs and of nothing else (for tests):
// the same candidates and sums as correspond_nested's overlap method.
struct RegionOverlap {
    ContourLink link;
    double area = 0.0;
};
std::vector<RegionOverlap> region_overlaps(NestedContours lower, NestedContours upper);

}  // namespace body
