#pragma once
// Colours for structures whose source gives none: perceptually distinct, with
// neighbours apart.
//
// distinct_palette(n) picks n colours by farthest-point sampling among light,
// in-gamut OKLab candidates, so any two are far apart (no two equal while the
// candidates last; beyond about 500 colours they repeat). assign_colours() hands these out so that structures whose
// bounds touch (neighbours on screen) get colours as different as possible:
// greedy, most-constrained structure first, each colour used once while
// colours last. Colours are sRGB-encoded components in [0, 1], like the label
// tables' colours they stand in for.
#include <array>
#include <optional>
#include <vector>

#include "shared/geometry.h"

namespace body::exhibit {

struct Box {
    Vec3 lo{0.0}, hi{0.0};
};

std::vector<Vec3> distinct_palette(size_t n);

// Perceptual distance of two sRGB colours (Euclidean in OKLab).
double colour_distance(const Vec3& a, const Vec3& b);

// Two structures are neighbours when their boxes, grown by `margin` (a fraction
// of the larger box's diagonal), overlap.
bool neighbours(const Box& a, const Box& b, double margin = 0.05);

// Keeps every given colour (`fixed[i]` set) and fills the others.
std::vector<Vec3> assign_colours(const std::vector<Box>& boxes, const std::vector<std::optional<Vec3>>& fixed);

}  // namespace body::exhibit
