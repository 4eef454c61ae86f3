// Chord heights by shape-based interpolation (see the header).
#include "builder/branching/chord_heights.h"

#include <algorithm>
#include <cmath>

namespace body {
namespace {

double distance_to_loop(const Vec2& p, std::span<const Vec2> loop) {
    double best = 1e300;
    for (size_t i = 0; i < loop.size(); ++i) {
        const Vec2 a = loop[i], ab = loop[(i + 1) % loop.size()] - a;
        const double l2 = glm::dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::length(a + ab * t - p));
    }
    return best;
}

}  // namespace

double loops_distance(const Vec2& p, std::span<const std::span<const Vec2>> loops) {
    double best = 1e300;
    for (const auto& loop : loops) best = std::min(best, distance_to_loop(p, loop));
    return best;
}

void blend_chord_heights(std::vector<Vec3>& positions, size_t first, std::span<const Vec2> single, double z_single,
                         std::span<const std::span<const Vec2>> branches, double z_branch, double lo, double hi) {
    for (size_t i = first; i < positions.size(); ++i) {
        const Vec2 p(positions[i]);
        const double d_s = distance_to_loop(p, single), d_b = loops_distance(p, branches);
        const double f = d_s + d_b > 0 ? d_s / (d_s + d_b) : 0.5;
        positions[i].z = z_single + (z_branch - z_single) * std::clamp(f, lo, hi);
    }
}

}  // namespace body
