#pragma once
// Correspondence: which contours on adjacent slices belong to the same piece of
// a structure.
//
// Contract: `lower` and `upper` are simple closed polygons (any orientation) on
// two adjacent slices, already split into solid boundaries or holes by the
// caller (a hole is only ever matched against holes). The result is a list of
// links (lower index, upper index), sorted, without duplicates. A contour with
// no link ends there (1:0); a contour linked to several is a branch (1:N, N:1,
// N:M). Coordinates are in the stack's units; no state is kept between calls.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

enum class CorrespondenceMethod {
    Overlap,  // 2-D boolean overlay: contours whose regions overlap are linked
    Ellipse,  // thesis: ellipse 5-tuples + overlap weight, minimum spanning path
};

const char* correspondence_method_name(CorrespondenceMethod method);

struct ContourLink {
    uint32_t lower = 0, upper = 0;
    bool operator==(const ContourLink&) const = default;
    auto operator<=>(const ContourLink&) const = default;
};

using PolygonSpan = std::span<const Vec2>;

std::vector<ContourLink> correspond_contours(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper,
                                             CorrespondenceMethod method);

// Area of the intersection of two simple polygons (either orientation), by
// Green's theorem over the parts of each boundary inside the other polygon.
double polygon_overlap_area(PolygonSpan a, PolygonSpan b);

// Region-overlap links (region_overlap.cpp) and thesis links (ellipse_graph.cpp).
std::vector<ContourLink> correspond_by_overlap(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper);
std::vector<ContourLink> correspond_by_ellipse(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper);

// Best-fit ellipse of a polygon from its area moments: centre, angle of the
// major axis in [0, pi), semi-axes a >= b (an ellipse's own moments give itself back).
struct Ellipse5 {
    double xc = 0, yc = 0, theta = 0, a = 0, b = 0;
};
Ellipse5 fit_ellipse(PolygonSpan polygon);

}  // namespace body
