// Marching squares on a binary mask (Lorensen & Cline 1987 in 2-D; the saddle
// rule fixed to a 4-connected inside, as in the consistent-topology variants of
// Nielson & Hamann 1991, "The asymptotic decider").
#include "builder/import/marching_squares.h"

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
    Vec2 midpoint(uint32_t id) const {
        if (id < horizontal_count) {
            long x = static_cast<long>(id) % (w + 1) - 1, y = static_cast<long>(id) / (w + 1) - 1;
            return {static_cast<double>(x) + 0.5, static_cast<double>(y)};
        }
        long v = static_cast<long>(id - horizontal_count);
        long x = v % (w + 2) - 1, y = v / (w + 2) - 1;
        return {static_cast<double>(x), static_cast<double>(y) + 0.5};
    }
};

// Phase 1: one directed segment per boundary crossing of every cell; next[e]
// is the edge the boundary leaves to after entering at edge e.
void link_cells(std::span<const uint8_t> mask, const EdgeGrid& g, std::vector<uint32_t>& next) {
    auto inside = [&](long x, long y) -> bool {
        if (x < 0 || y < 0 || x >= g.w || y >= g.h) return false;
        return mask[static_cast<size_t>(y * g.w + x)] != 0;
    };
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
                // Saddle: cut around each inside corner separately (4-connected inside).
                if (corner[0]) {
                    next[edge[0]] = edge[3];  // around a
                    next[edge[2]] = edge[1];  // around c
                } else {
                    next[edge[1]] = edge[0];  // around b
                    next[edge[3]] = edge[2];  // around d
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
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x) == 0.0;  // exact: half-integers
}

// Phase 2: follow next[] into closed rings, dropping collinear vertices.
void follow_rings(const EdgeGrid& g, std::vector<uint32_t>& next, std::vector<std::vector<Vec2>>& rings) {
    std::vector<Vec2> ring;
    for (uint32_t start = 0; start < next.size(); ++start) {
        if (next[start] == kNone) continue;
        ring.clear();
        uint32_t e = start;
        while (next[e] != kNone) {
            ring.push_back(g.midpoint(e));
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
    EdgeGrid g;
    g.w = static_cast<long>(width);
    g.h = static_cast<long>(height);
    g.horizontal_count = static_cast<uint32_t>((g.h + 2) * (g.w + 1));
    std::vector<uint32_t> next(g.horizontal_count + static_cast<size_t>((g.h + 1) * (g.w + 2)), kNone);
    link_cells(mask, g, next);
    follow_rings(g, next, rings);
}

}  // namespace body
