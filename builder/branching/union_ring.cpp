// Union-ring branching: a raster outline of the group's regions at mid-slice.
#include "builder/branching/union_ring.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "builder/branching/nested_region.h"
#include "builder/contours/validate.h"

namespace body {
namespace {

struct Grid {
    Vec2 origin{0.0};
    double cell = 0;
    long nx = 0, ny = 0;
    std::vector<uint8_t> mask;
    uint8_t& at(long i, long j) { return mask[size_t(j * nx + i)]; }
};

// Phase 1: a grid over the loops' box with a margin of four cells.
Grid grid_around(std::span<const std::span<const Vec2>> loops, double cell) {
    Aabb box;
    for (const auto& l : loops)
        for (const Vec2& p : l) box.extend(Vec3(p, 0.0));
    Grid g;
    if (box.empty() || !(cell > 0)) return g;
    const Vec2 lo(box.min), hi(box.max);
    while ((hi.x - lo.x) / cell * ((hi.y - lo.y) / cell) > 4e6) cell *= 1.5;
    g.cell = cell;
    g.origin = lo - Vec2(4 * cell);
    g.nx = long(std::ceil((hi.x - lo.x) / cell)) + 8;
    g.ny = long(std::ceil((hi.y - lo.y) / cell)) + 8;
    g.mask.assign(size_t(g.nx * g.ny), 0);
    return g;
}

// Phase 2: interiors by scanlines through the cell centres (even-odd per loop).
void fill_interiors(Grid& g, std::span<const std::span<const Vec2>> loops) {
    std::vector<double> xs;
    for (long j = 0; j < g.ny; ++j) {
        const double y = g.origin.y + (double(j) + 0.5) * g.cell;
        for (const auto& l : loops) {
            xs.clear();
            for (size_t k = 0; k < l.size(); ++k) {
                const Vec2 a = l[k], b = l[(k + 1) % l.size()];
                if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
            std::sort(xs.begin(), xs.end());
            for (size_t k = 0; k + 1 < xs.size(); k += 2) {
                const long i0 = std::max(0L, long(std::ceil((xs[k] - g.origin.x) / g.cell - 0.5)));
                const long i1 = std::min(g.nx - 1, long(std::floor((xs[k + 1] - g.origin.x) / g.cell - 0.5)));
                for (long i = i0; i <= i1; ++i) g.at(i, j) = 1;
            }
        }
    }
}

// Phase 3: cells the loops pass through (thin parts have no cell centre inside).
void mark_boundaries(Grid& g, std::span<const std::span<const Vec2>> loops) {
    for (const auto& l : loops)
        for (size_t k = 0; k < l.size(); ++k) {
            const Vec2 a = l[k], b = l[(k + 1) % l.size()];
            const int steps = 1 + int(std::ceil(4 * glm::length(b - a) / g.cell));
            for (int t = 0; t <= steps; ++t) {
                const Vec2 p = a + (b - a) * (double(t) / steps);
                g.at(long((p.x - g.origin.x) / g.cell), long((p.y - g.origin.y) / g.cell)) = 1;
            }
        }
}

// Phase 4: grow by one cell (8-neighbourhood).
void grow(Grid& g) {
    std::vector<uint8_t> grown(g.mask.size(), 0);
    for (long j = 1; j + 1 < g.ny; ++j)
        for (long i = 1; i + 1 < g.nx; ++i)
            for (long dj = -1; dj <= 1; ++dj)
                for (long di = -1; di <= 1; ++di)
                    if (g.at(i + di, j + dj)) grown[size_t(j * g.nx + i)] = 1;
    g.mask.swap(grown);
}

// Phase 5: fill holes and diagonal-only contacts until neither is left.
void fill_holes_and_saddles(Grid& g) {
    const long nx = g.nx, ny = g.ny;
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<uint8_t> outside(g.mask.size(), 0);
        std::vector<long> stack{0};
        outside[0] = 1;
        while (!stack.empty()) {
            const long c = stack.back();
            stack.pop_back();
            const long i = c % nx, j = c / nx;
            const long next[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
            for (const auto& q : next) {
                if (q[0] < 0 || q[1] < 0 || q[0] >= nx || q[1] >= ny) continue;
                const long d = q[1] * nx + q[0];
                if (!g.mask[size_t(d)] && !outside[size_t(d)]) outside[size_t(d)] = 1, stack.push_back(d);
            }
        }
        for (size_t c = 0; c < g.mask.size(); ++c)
            if (!g.mask[c] && !outside[c]) g.mask[c] = 1, changed = true;
        for (long j = 0; j + 1 < ny; ++j)
            for (long i = 0; i + 1 < nx; ++i) {
                const int a = g.at(i, j), b = g.at(i + 1, j), c = g.at(i + 1, j + 1), d = g.at(i, j + 1);
                if (a == c && b == d && a != b)
                    g.at(i, j) = g.at(i + 1, j) = g.at(i + 1, j + 1) = g.at(i, j + 1) = 1, changed = true;
            }
    }
}

// Phase 6: marching squares, per block one directed step, from the side where
// the counter-clockwise walk round the block leaves the mask to where it
// enters; the steps are followed once round. Nodes on doubled integer
// coordinates: horizontal side (i,j)-(i+1,j) at (2i+2, 2j+1), vertical side
// (i,j)-(i,j+1) at (2i+1, 2j+2). Empty when the steps make more than one loop.
std::vector<std::pair<long, long>> trace_boundary(Grid& g) {
    const long nx = g.nx, ny = g.ny;
    auto h_side = [&](long i, long j) { return 2 * (j * nx + i); };
    auto v_side = [&](long i, long j) { return 2 * (j * nx + i) + 1; };
    std::map<long, long> next;
    for (long j = 0; j + 1 < ny; ++j)
        for (long i = 0; i + 1 < nx; ++i) {
            const int v[4] = {g.at(i, j), g.at(i + 1, j), g.at(i + 1, j + 1), g.at(i, j + 1)};
            const long side[4] = {h_side(i, j), v_side(i + 1, j), h_side(i, j + 1), v_side(i, j)};
            long exit = -1, entry = -1;
            for (int k = 0; k < 4; ++k) {
                if (v[k] && !v[(k + 1) % 4]) exit = side[k];
                if (!v[k] && v[(k + 1) % 4]) entry = side[k];
            }
            if (exit >= 0 && entry >= 0) next[exit] = entry;
        }
    if (next.empty()) return {};
    auto node = [&](long key) {
        const long c = key / 2, i = c % nx, j = c / nx;
        return key % 2 == 0 ? std::pair<long, long>{2 * i + 2, 2 * j + 1} : std::pair<long, long>{2 * i + 1, 2 * j + 2};
    };
    std::vector<std::pair<long, long>> ring;
    const long start = next.begin()->first;
    for (long key = start;;) {
        ring.push_back(node(key));
        auto it = next.find(key);
        if (it == next.end()) return {};
        key = it->second;
        if (key == start) break;
        if (ring.size() > next.size()) return {};
    }
    if (ring.size() != next.size()) return {};  // more than one piece
    return ring;
}

// Phase 7: the ring's corners (collinear runs merged) in xy.
std::vector<Vec2> corners(const Grid& g, const std::vector<std::pair<long, long>>& ring) {
    std::vector<Vec2> out;
    const size_t n = ring.size();
    for (size_t k = 0; k < n; ++k) {
        const auto& p = ring[(k + n - 1) % n];
        const auto& q = ring[k];
        const auto& r = ring[(k + 1) % n];
        if ((q.first - p.first) * (r.second - q.second) == (q.second - p.second) * (r.first - q.first)) continue;
        out.push_back(g.origin + Vec2(double(q.first), double(q.second)) * (0.5 * g.cell));
    }
    return out;
}

// The grid spacing: half the mean edge length of the loops, within
// [1/4000, 1/100] of the group's extent.
double cell_size(std::span<const std::span<const Vec2>> loops) {
    double perimeter = 0;
    size_t points = 0;
    Aabb box;
    for (const auto& l : loops)
        for (size_t i = 0; i < l.size(); ++i) {
            perimeter += glm::length(l[(i + 1) % l.size()] - l[i]);
            box.extend(Vec3(l[i], 0.0));
        }
    for (const auto& l : loops) points += l.size();
    return std::clamp(0.5 * perimeter / double(points), box.extent() / 4000, box.extent() / 100);
}

}  // namespace

std::vector<Vec2> union_ring(std::span<const std::span<const Vec2>> loops, double cell) {
    Grid g = grid_around(loops, cell);
    if (g.mask.empty()) return {};
    fill_interiors(g, loops);
    mark_boundaries(g, loops);
    grow(g);
    fill_holes_and_saddles(g);
    const std::vector<std::pair<long, long>> ring = trace_boundary(g);
    if (ring.empty()) return {};
    return corners(g, ring);
}

Status connect_union_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                          std::span<const uint32_t> gu, bool hole) {
    std::vector<std::span<const Vec2>> all;
    for (uint32_t k : gl) all.emplace_back(surface.loops[s][k].xy);
    for (uint32_t k : gu) all.emplace_back(surface.loops[s + 1][k].xy);
    std::vector<Vec2> ring = union_ring(all, cell_size(all));
    if (ring.size() < 3) return input_error("no union ring");
    if (hole) std::reverse(ring.begin(), ring.end());
    for (const auto& l : all)
        for (const Vec2& p : l)
            if (!point_in_polygon(p, ring)) return input_error("union ring misses a contour");
    // Short walls at the ring: the ring is the widest outline of the pair, and
    // the sheets reach the contours sooner.
    return connect_through_ring(surface, s, gl, gu, ring, hole, 0.1);
}

}  // namespace body
