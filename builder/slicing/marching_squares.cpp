// Marching squares on a binary mask and on a scalar field (Lorensen & Cline
// 1987 in 2-D; the saddle rule fixed per cell, as in the consistent-topology
// variants of Nielson & Hamann 1991, "The asymptotic decider": the mask's
// inside 4-connected, the field's inside corners joined when the cell's mean is
// above the level).
#include "builder/slicing/marching_squares.h"

#include <algorithm>
#include <cassert>

namespace body {
namespace {

constexpr uint32_t kNone = 0xffffffffu;

// Edge ids over a grid padded by one outside pixel on every side.
// Horizontal edge between pixels (x, y) and (x + 1, y), x in [-1, w-1], y in [-1, h]:
//   (y + 1) * (w + 1) + (x + 1).
// Vertical edge between pixels (x, y) and (x, y + 1), x in [-1, w], y in [-1, h-1]:
//   horizontal_count + (y + 1) * (w + 2) + (x + 1).
struct EdgeGrid {
    long w = 0, h = 0;
    uint32_t horizontal_count = 0;

    uint32_t horizontal(long x, long y) const { return static_cast<uint32_t>((y + 1) * (w + 1) + (x + 1)); }
    uint32_t vertical(long x, long y) const {
        return horizontal_count + static_cast<uint32_t>((y + 1) * (w + 2) + (x + 1));
    }
    // The edge's first pixel (x, y); the second is (x + 1, y) or (x, y + 1).
    bool first_pixel(uint32_t id, long& x, long& y) const {
        if (id < horizontal_count) {
            x = static_cast<long>(id) % (w + 1) - 1, y = static_cast<long>(id) / (w + 1) - 1;
            return true;  // horizontal
        }
        long v = static_cast<long>(id - horizontal_count);
        x = v % (w + 2) - 1, y = v / (w + 2) - 1;
        return false;
    }
    Vec2 midpoint(uint32_t id) const {
        long x = 0, y = 0;
        if (first_pixel(id, x, y)) return {static_cast<double>(x) + 0.5, static_cast<double>(y)};
        return {static_cast<double>(x), static_cast<double>(y) + 0.5};
    }
    // Every edge id's slot in `next`, unlinked.
    size_t edge_count() const { return horizontal_count + static_cast<size_t>((h + 1) * (w + 2)); }
};

EdgeGrid edge_grid(size_t width, size_t height) {
    EdgeGrid g;
    g.w = static_cast<long>(width);
    g.h = static_cast<long>(height);
    g.horizontal_count = static_cast<uint32_t>((g.h + 2) * (g.w + 1));
    return g;
}

// Phase 1: one directed segment per boundary crossing of every cell; next[e]
// is the edge the boundary leaves to after entering at edge e. `inside(x, y)`
// classifies pixels (false outside the grid); `join(cx, cy)` says whether a
// saddle cell's two inside corners are connected through the cell.
template <typename Inside, typename Join>
void link_cells(const EdgeGrid& g, Inside inside, Join join, std::vector<uint32_t>& next) {
    for (long cy = -1; cy < g.h; ++cy) {
        for (long cx = -1; cx < g.w; ++cx) {
            // Corners counter-clockwise: a (cx,cy), b (cx+1,cy), c (cx+1,cy+1), d (cx,cy+1).
            const bool corner[4] = {inside(cx, cy), inside(cx + 1, cy), inside(cx + 1, cy + 1), inside(cx, cy + 1)};
            const int n_in = corner[0] + corner[1] + corner[2] + corner[3];
            if (n_in == 0 || n_in == 4) continue;
            // Cell edges in the same order: bottom (a-b), right (b-c), top (c-d), left (d-a).
            const uint32_t edge[4] = {g.horizontal(cx, cy), g.vertical(cx + 1, cy), g.horizontal(cx, cy + 1),
                                      g.vertical(cx, cy)};
            if (n_in == 2 && corner[0] == corner[2]) {
                // Saddle: cut around each inside corner (separate), or around
                // each outside corner (the inside joined across the cell).
                const bool joined = join(cx, cy);
                if (corner[0] && !joined) {
                    next[edge[0]] = edge[3];  // around a
                    next[edge[2]] = edge[1];  // around c
                } else if (corner[0]) {
                    next[edge[0]] = edge[1];  // around b
                    next[edge[2]] = edge[3];  // around d
                } else if (!joined) {
                    next[edge[1]] = edge[0];  // around b
                    next[edge[3]] = edge[2];  // around d
                } else {
                    next[edge[1]] = edge[2];  // around c
                    next[edge[3]] = edge[0];  // around a
                }
                continue;
            }
            // One crossing leaves the inside (in -> out along the cell boundary),
            // one enters it; the segment runs from the first to the second so the
            // inside stays on the left.
            uint32_t from = kNone, to = kNone;
            for (int e = 0; e < 4; ++e) {
                const bool p = corner[e], q = corner[(e + 1) % 4];
                if (p && !q) from = edge[e];
                if (!p && q) to = edge[e];
            }
            assert(from != kNone && to != kNone);
            next[from] = to;
        }
    }
}

bool collinear(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) == 0.0;  // exact for half-integers
}

// Phase 2: follow next[] into closed rings, dropping collinear vertices;
// `point(e)` is where the boundary crosses edge e.
template <typename Point>
void follow_rings(std::vector<uint32_t>& next, Point point, std::vector<std::vector<Vec2>>& rings) {
    std::vector<Vec2> ring;
    for (uint32_t start = 0; start < next.size(); ++start) {
        if (next[start] == kNone) continue;
        ring.clear();
        uint32_t e = start;
        while (next[e] != kNone) {
            ring.push_back(point(e));
            uint32_t n = next[e];
            next[e] = kNone;
            e = n;
        }
        assert(e == start);
        std::vector<Vec2> kept;
        kept.reserve(ring.size());
        const size_t n = ring.size();
        for (size_t i = 0; i < n; ++i) {
            if (!collinear(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n])) kept.push_back(ring[i]);
        }
        if (kept.size() >= 3) rings.push_back(std::move(kept));
    }
}

}  // namespace

void trace_mask_boundaries(std::span<const uint8_t> mask, size_t width, size_t height,
                           std::vector<std::vector<Vec2>>& rings) {
    assert(mask.size() >= width * height);
    rings.clear();
    if (width == 0 || height == 0) return;
    const EdgeGrid g = edge_grid(width, height);
    std::vector<uint32_t> next(g.edge_count(), kNone);
    auto inside = [&](long x, long y) -> bool {
        if (x < 0 || y < 0 || x >= g.w || y >= g.h) return false;
        return mask[static_cast<size_t>(y * g.w + x)] != 0;
    };
    link_cells(
        g, inside, [](long, long) { return false; }, next);
    follow_rings(
        next, [&](uint32_t e) { return g.midpoint(e); }, rings);
}

void trace_field_isolines(std::span<const float> field, size_t width, size_t height, float level,
                          std::vector<std::vector<Vec2>>& rings) {
    assert(field.size() >= width * height && level > 0.0f);
    rings.clear();
    if (width == 0 || height == 0) return;
    const EdgeGrid g = edge_grid(width, height);
    std::vector<uint32_t> next(g.edge_count(), kNone);
    auto value = [&](long x, long y) -> double {
        if (x < 0 || y < 0 || x >= g.w || y >= g.h) return 0.0;
        return field[static_cast<size_t>(y * g.w + x)];
    };
    auto inside = [&](long x, long y) { return value(x, y) > level; };
    auto join = [&](long cx, long cy) {
        const double sum = value(cx, cy) + value(cx + 1, cy) + value(cx + 1, cy + 1) + value(cx, cy + 1);
        return sum > 4.0 * level;
    };
    link_cells(g, inside, join, next);
    // Linear along the edge, kept kEdgeMargin off the pixel centres so that
    // two crossings never meet at a centre whose value equals the level.
    constexpr double kEdgeMargin = 1.0 / 128.0;
    auto point = [&](uint32_t e) -> Vec2 {
        long x = 0, y = 0;
        const bool horizontal = g.first_pixel(e, x, y);
        const double v0 = value(x, y), v1 = horizontal ? value(x + 1, y) : value(x, y + 1);
        const double t = std::clamp((level - v0) / (v1 - v0), kEdgeMargin, 1.0 - kEdgeMargin);
        if (horizontal) return {static_cast<double>(x) + t, static_cast<double>(y)};
        return {static_cast<double>(x), static_cast<double>(y) + t};
    };
    follow_rings(next, point, rings);
}

}  // namespace body
