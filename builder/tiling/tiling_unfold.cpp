// Fold check and repair for a tiled band: a band whose triangles cross each
// other (the band folds through itself, which the corner charge of the cost
// does not always see: jagged or strongly shifted pairs) is repaired by
// diagonal flips, each flip chosen greedily as the one that leaves the fewest
// crossing triangle pairs (ties: the lower (folds, area) cost), until no
// crossing is left or no flip lowers their number. Only triangles taking part
// in a crossing, and their neighbours on the path, are candidates.
//
// The check is in two steps. A band between two planar contours at different
// heights is cut at a few heights: the points at parameter t along every
// spanning edge form a closed polygon lying on the band (one segment per
// triangle), and two triangles that cross make two of its segments cross at
// some t. Segments are short (a fraction of the contour edges), so a uniform
// 2-D grid finds crossings in linear time. Only a band whose sections cross
// (in projection onto the slice plane) gets the exact triangle-pair test,
// whose box broad phase is slow on the long thin triangles of a band; small
// bands get it directly. A crossing that no section meets (one confined
// close to a contour) can go unseen on large bands.
//
// References:
// - D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//   1992 (the band as a path of spanning edges; local diagonal swaps).
// - BodyGen/BodyView issue 3: "Bands must not self-intersect; where a cost
//   choice would fold, pick the non-folding one."
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "builder/tiling/tiling_internal.h"
#include "shared/mesh_intersect.h"

namespace body::tiling_detail {

namespace {

struct Scratch {
    std::vector<Vec3> positions;  // lower then upper
    std::vector<uint32_t> triangles;
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
};

// Bands up to this many triangles skip the section test: the exact test is
// cheap enough for them.
constexpr size_t kExactTriangles = 256;

// Sections at these parameters along the spanning edges (k / kSections, k in
// [1, kSections)): 1/4, 1/2 and 3/4.
constexpr int kSections = 4;

// Do segments (a, b) and (c, d) cross or touch (2-D)?
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    auto orient = [](const Vec2& p, const Vec2& q, const Vec2& r) {
        const double v = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
        return v > 0 ? 1 : v < 0 ? -1 : 0;
    };
    const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    auto within = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on segment pq, given collinear
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    return (o1 == 0 && within(a, b, c)) || (o2 == 0 && within(a, b, d)) || (o3 == 0 && within(c, d, a)) ||
           (o4 == 0 && within(c, d, b));
}

// Scratch of the section test: an open-addressing hash of grid cells, each
// holding a list of the segments entered so far.
struct SectionGrid {
    std::vector<Vec2> points;
    struct Slot {
        uint64_t key = 0;  // cell key + 1 (0 = empty)
        uint32_t head = ~0u;
    };
    std::vector<Slot> slots;
    std::vector<uint32_t> entry_next, entry_seg;  // per entry
};

// Phase 0: does any section of the band cross itself (seen from +z)? Each
// segment is tested on entry against the segments already in its cells.
bool sections_cross(const CyclicTiling& tiling, SectionGrid& g) {
    constexpr uint32_t kNone = ~0u;
    const size_t count = tiling.size();
    const auto& lower = tiling.band->lower;
    const auto& upper = tiling.band->upper;
    for (int k = 1; k < kSections; ++k) {
        const double t = double(k) / kSections;
        g.points.resize(count);
        double length = 0;
        Vec2 lo(1e300);
        for (size_t p = 0; p < count; ++p) {
            const Vec3 q = lower[tiling.ei[p]] + (upper[tiling.ej[p]] - lower[tiling.ei[p]]) * t;
            g.points[p] = Vec2(q.x, q.y);
            lo = glm::min(lo, g.points[p]);
        }
        for (size_t p = 0; p < count; ++p) length += glm::length(g.points[tiling.next(p)] - g.points[p]);
        const double cell = std::max(2 * length / double(count), 1e-300);
        size_t slots = 16;
        while (slots < 4 * count) slots *= 2;
        g.slots.assign(slots, SectionGrid::Slot{});
        g.entry_next.clear();
        g.entry_seg.clear();
        for (size_t p = 0; p < count; ++p) {
            const Vec2 a = g.points[p], b = g.points[tiling.next(p)];
            const uint64_t x0 = uint64_t((std::min(a.x, b.x) - lo.x) / cell),
                           x1 = uint64_t((std::max(a.x, b.x) - lo.x) / cell);
            const uint64_t y0 = uint64_t((std::min(a.y, b.y) - lo.y) / cell),
                           y1 = uint64_t((std::max(a.y, b.y) - lo.y) / cell);
            for (uint64_t y = y0; y <= y1; ++y)
                for (uint64_t x = x0; x <= x1; ++x) {
                    const uint64_t key = ((y << 32) ^ x) + 1;
                    // Tiles of 8 x 8 cells get 64 consecutive slots: the curve walks memory in order.
                    const uint64_t tile = ((x >> 3) * 0x9E3779B1ull) ^ ((y >> 3) * 0x85EBCA77ull);
                    size_t slot = size_t((tile << 6) + ((y & 7) << 3) + (x & 7)) & (slots - 1);
                    while (g.slots[slot].key != 0 && g.slots[slot].key != key) slot = (slot + 1) & (slots - 1);
                    SectionGrid::Slot& cell_slot = g.slots[slot];
                    if (cell_slot.key == 0) {
                        if (2 * (g.entry_seg.size() + 1) > slots) return true;  // a pathological band: test exactly
                        cell_slot.key = key;
                    }
                    for (uint32_t e = cell_slot.head; e != kNone; e = g.entry_next[e]) {
                        const size_t q = g.entry_seg[e];
                        if (q == tiling.next(p) || p == tiling.next(q)) continue;  // neighbours share a point
                        if (segments_meet(a, b, g.points[q], g.points[tiling.next(q)])) return true;
                    }
                    g.entry_next.push_back(cell_slot.head);
                    g.entry_seg.push_back(uint32_t(p));
                    cell_slot.head = uint32_t(g.entry_seg.size() - 1);
                }
        }
    }
    return false;
}

// Phase 1: the crossing triangle pairs of the band as it stands.
size_t crossings(const CyclicTiling& tiling, Scratch& s, bool want_pairs) {
    s.triangles.clear();
    tiling.emit(s.triangles);
    s.pairs.clear();
    return count_self_intersections(s.positions, s.triangles, 0, want_pairs ? &s.pairs : nullptr);
}

// Phase 2: the spanning edges whose flip may remove a crossing: both edges of
// every crossing triangle and of its neighbours on the path.
void candidates(const CyclicTiling& tiling, const Scratch& s, std::vector<uint32_t>& out) {
    out.clear();
    for (const auto& [a, b] : s.pairs)
        for (uint32_t t : {a, b})
            for (size_t p : {tiling.prev(t), size_t(t), tiling.next(t), tiling.next(tiling.next(t))})
                out.push_back(uint32_t(p));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool keeps_runs(const CyclicTiling& tiling, size_t p) {
    const size_t q = tiling.prev(p);
    return tiling.run_length(q) <= tiling.run_limit(tiling.mv[q]) &&
           tiling.run_length(p) <= tiling.run_limit(tiling.mv[p]);
}

// Bands up to this many triangles may try pairs of flips when no single flip
// lowers the crossings (quadratic in the band per round).
constexpr size_t kPairSearchTriangles = 96;

// Phase 3: the first pair of flips (a candidate, then any spanning edge) that
// lowers the crossings below `current`; applied when found.
bool flip_pair(CyclicTiling& tiling, Scratch& s, const std::vector<uint32_t>& flips, size_t current) {
    for (uint32_t p : flips) {
        if (!tiling.flippable(p)) continue;
        tiling.flip(p);
        if (keeps_runs(tiling, p))
            for (size_t q = 0; q < tiling.size(); ++q) {
                if (q == p || !tiling.flippable(q)) continue;
                tiling.flip(q);
                if (keeps_runs(tiling, q) && crossings(tiling, s, false) < current) return true;
                tiling.flip(q);
            }
        tiling.flip(p);
    }
    return false;
}

}  // namespace

size_t unfold(CyclicTiling& tiling) {
    if (tiling.size() > kExactTriangles) {
        SectionGrid grid;
        if (!sections_cross(tiling, grid)) return 0;
    }
    Scratch s;
    s.positions.assign(tiling.band->lower.begin(), tiling.band->lower.end());
    s.positions.insert(s.positions.end(), tiling.band->upper.begin(), tiling.band->upper.end());
    size_t current = crossings(tiling, s, true);
    if (current == 0) return 0;
    std::vector<uint32_t> flips;
    // Each accepted flip removes at least one crossing: at most `current` rounds.
    for (size_t round = 0, limit = current; round < limit && current > 0; ++round) {
        candidates(tiling, s, flips);
        size_t best_count = current, best_flip = tiling.size();
        Cost best_cost = tiling.total();
        for (uint32_t p : flips) {
            if (!tiling.flippable(p)) continue;
            tiling.flip(p);
            if (keeps_runs(tiling, p)) {
                const size_t count = crossings(tiling, s, false);
                const Cost cost = tiling.total();
                if (count < best_count || (count == best_count && best_flip < tiling.size() && cost < best_cost)) {
                    best_count = count;
                    best_flip = p;
                    best_cost = cost;
                }
            }
            tiling.flip(p);  // a second flip restores the previous state
        }
        if (best_flip == tiling.size()) {
            // Stuck: on small bands, a pair of flips (a candidate, then any edge).
            if (tiling.size() > kPairSearchTriangles || !flip_pair(tiling, s, flips, current)) break;
        } else {
            tiling.flip(best_flip);
        }
        current = crossings(tiling, s, true);
    }
    return current;
}

}  // namespace body::tiling_detail
