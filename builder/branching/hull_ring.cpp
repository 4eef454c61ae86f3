// Hull-ring branching: a mid-slice convex hull between the group's two sides.
#include "builder/branching/hull_ring.h"

#include <algorithm>

#include "builder/branching/nested_region.h"
#include "builder/branching/partition_bands.h"

namespace body {
namespace {

// No loop of the structure nested inside any of `members` on slice s.
bool without_children(const StructureSurface& surface, size_t s, std::span<const uint32_t> members) {
    for (const Loop& l : surface.loops[s])
        for (uint32_t m : members)
            if (l.parent == int(m)) return false;
    return true;
}

}  // namespace

std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
    std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    std::vector<Vec2> h(2 * p.size());
    size_t k = 0;
    auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
        return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
        h[k++] = p[i - 1];
    }
    h.resize(k - 1);
    return h;
}

Status connect_hull_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                         std::span<const uint32_t> gu, bool hole) {
    const Loop& first_lower = surface.loops[s][gl[0]];
    const double zl = surface.z[s], zu = surface.z[s + 1];
    std::vector<Vec2> pts;
    for (uint32_t k : gl) pts.insert(pts.end(), surface.loops[s][k].xy.begin(), surface.loops[s][k].xy.end());
    for (uint32_t k : gu) pts.insert(pts.end(), surface.loops[s + 1][k].xy.begin(), surface.loops[s + 1][k].xy.end());
    std::vector<Vec2> hull = convex_hull(pts);
    if (hole) std::reverse(hull.begin(), hull.end());  // rings run clockwise around voids
    const double zm = 0.5 * (zl + zu);
    if (without_children(surface, s, gl) && without_children(surface, s + 1, gu)) {
        Vec2 centre(0.0);
        for (const Vec2& p : hull) centre += p;
        centre /= double(hull.size());
        for (Vec2& p : hull) p = centre + (p - centre) * 1.01;
        return connect_through_ring(surface, s, gl, gu, hull, hole, 1.0 / 3);
    }
    std::vector<uint32_t> mid = lifted_copy(surface, hull, zm);
    auto status = split_into_bands(surface, mid, surface.loops[s], gl, 0.5 * (zl + zm), false, first_lower);
    if (!status) return status;
    return split_into_bands(surface, mid, surface.loops[s + 1], gu, 0.5 * (zm + zu), true, first_lower);
}

}  // namespace body
