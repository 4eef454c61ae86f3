// Ring simplification.
// - Douglas & Peucker, "Algorithms for the reduction of the number of points
//   required to represent a digitized line or its caricature", Cartographica 1973.
// - Topology safeguard in the spirit of Saalfeld, "Topologically consistent line
//   simplification with the Douglas-Peucker algorithm", CaGIS 1999: simplified
//   results are checked for intersections and nesting, offending rings retried.
#include "builder/import/ring_simplify.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace body {
namespace {

double point_segment_distance2(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    double t = len2 > 0.0 ? glm::dot(p - a, ab) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const Vec2 d = p - (a + t * ab);
    return glm::dot(d, d);
}

// Phase 1: Douglas-Peucker on a closed ring, anchored at its lowest-leftmost
// vertex and the vertex farthest from it.
std::vector<Vec2> douglas_peucker_ring(const std::vector<Vec2>& ring, double tolerance) {
    const size_t n = ring.size();
    if (n <= 3) return ring;
    size_t a = 0;
    for (size_t i = 1; i < n; ++i) {
        if (ring[i].y < ring[a].y || (ring[i].y == ring[a].y && ring[i].x < ring[a].x)) a = i;
    }
    size_t b = a;
    double far = -1.0;
    for (size_t i = 0; i < n; ++i) {
        const Vec2 d = ring[i] - ring[a];
        if (glm::dot(d, d) > far) far = glm::dot(d, d), b = i;
    }
    std::vector<uint8_t> keep(n, 0);
    keep[a] = keep[b] = 1;
    const double tol2 = tolerance * tolerance;
    // Spans are (first, count) in ring order starting at `first`, mod n.
    std::vector<std::pair<size_t, size_t>> stack = {{a, (b + n - a) % n}, {b, (a + n - b) % n}};
    while (!stack.empty()) {
        auto [first, count] = stack.back();
        stack.pop_back();
        if (count < 2) continue;
        const Vec2& p = ring[first];
        const Vec2& q = ring[(first + count) % n];
        size_t worst = 0;
        double worst_d = -1.0;
        for (size_t k = 1; k < count; ++k) {
            const double d = point_segment_distance2(ring[(first + k) % n], p, q);
            if (d > worst_d) worst_d = d, worst = k;
        }
        if (worst_d > tol2) {
            keep[(first + worst) % n] = 1;
            stack.push_back({first, worst});
            stack.push_back({(first + worst) % n, count - worst});
        }
    }
    std::vector<Vec2> out;
    for (size_t i = 0; i < n; ++i) {
        if (keep[i]) out.push_back(ring[i]);
    }
    if (out.size() < 3) return ring;
    return out;
}

// Small rings keep their shape: a few-voxel region simplified to a triangle
// loses most of its area (branch partitions no longer need the vertices: they
// add their own where a contour has too few for its branches).
// When Douglas-Peucker leaves fewer than min(n, kMinKeptVertices) vertices, the
// dropped vertex farthest from its kept segment is restored, repeatedly.
constexpr size_t kMinKeptVertices = 8;

std::vector<Vec2> simplify_ring(const std::vector<Vec2>& ring, double tolerance) {
    const size_t n = ring.size();
    const size_t wanted = std::min(n, kMinKeptVertices);
    std::vector<Vec2> out = douglas_peucker_ring(ring, tolerance);
    if (out.size() >= wanted) return out;
    std::vector<uint8_t> keep(n, 0);
    for (size_t i = 0, j = 0; i < n && j < out.size(); ++i) {
        if (ring[i] == out[j]) keep[i] = 1, ++j;
    }
    for (size_t kept = out.size(); kept < wanted; ++kept) {
        size_t best = SIZE_MAX;
        double best_d = -1.0;
        size_t first = 0;
        while (!keep[first]) ++first;
        for (size_t s = 0; s < n; ++s) {  // spans between consecutive kept vertices
            const size_t a = (first + s) % n;
            if (!keep[a]) continue;
            size_t b = (a + 1) % n;
            while (!keep[b]) b = (b + 1) % n;
            for (size_t k = (a + 1) % n; k != b; k = (k + 1) % n) {
                const double d = point_segment_distance2(ring[k], ring[a], ring[b]);
                if (d > best_d) best_d = d, best = k;
            }
        }
        if (best == SIZE_MAX) break;
        keep[best] = 1;
    }
    out.clear();
    for (size_t i = 0; i < n; ++i) {
        if (keep[i]) out.push_back(ring[i]);
    }
    return out;
}

int orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    const double d = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    return (d > 0.0) - (d < 0.0);
}

bool within_box(const Vec2& a, const Vec2& b, const Vec2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Closed segments [p1,p2] and [q1,q2] share at least one point.
bool segments_touch(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
    const int o1 = orient(p1, p2, q1), o2 = orient(p1, p2, q2), o3 = orient(q1, q2, p1), o4 = orient(q1, q2, p2);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;  // proper crossing
    if (o1 == 0 && within_box(p1, p2, q1)) return true;
    if (o2 == 0 && within_box(p1, p2, q2)) return true;
    if (o3 == 0 && within_box(q1, q2, p1)) return true;
    if (o4 == 0 && within_box(q1, q2, p2)) return true;
    return false;
}

struct SegmentRef {
    uint32_t ring;
    uint32_t index;  // segment from point index to index + 1 (mod size)
};

// Phase 2: flags every ring that has a segment touching a non-adjacent
// segment (of any ring), or folds back at a vertex. A uniform grid keeps the
// pair tests local.
void flag_intersections(const std::vector<std::vector<Vec2>>& rings, std::vector<uint8_t>& bad) {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    size_t segment_count = 0;
    for (const auto& r : rings) {
        for (const Vec2& p : r) lo = glm::min(lo, p), hi = glm::max(hi, p);
        segment_count += r.size();
    }
    if (segment_count == 0) return;
    // Fold-backs at a vertex: the two segments are collinear and overlap.
    for (size_t ri = 0; ri < rings.size(); ++ri) {
        const auto& r = rings[ri];
        const size_t n = r.size();
        for (size_t i = 0; i < n; ++i) {
            const Vec2& a = r[(i + n - 1) % n];
            const Vec2& b = r[i];
            const Vec2& c = r[(i + 1) % n];
            if (orient(a, b, c) == 0 && glm::dot(a - b, c - b) > 0.0) bad[ri] = 1;
        }
    }
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    const double cell = std::max(1.0, extent / std::max(1.0, std::sqrt(static_cast<double>(segment_count))));
    const long gw = static_cast<long>((hi.x - lo.x) / cell) + 1;
    std::unordered_map<long, std::vector<SegmentRef>> grid;
    grid.reserve(segment_count * 2);
    auto cell_of = [&](double v, double origin) { return static_cast<long>((v - origin) / cell); };
    auto segment = [&](const SegmentRef& s, Vec2& a, Vec2& b) {
        const auto& r = rings[s.ring];
        a = r[s.index];
        b = r[(s.index + 1) % r.size()];
    };
    for (uint32_t ri = 0; ri < rings.size(); ++ri) {
        for (uint32_t i = 0; i < rings[ri].size(); ++i) {
            Vec2 a, b;
            segment({ri, i}, a, b);
            const long x0 = cell_of(std::min(a.x, b.x), lo.x), x1 = cell_of(std::max(a.x, b.x), lo.x);
            const long y0 = cell_of(std::min(a.y, b.y), lo.y), y1 = cell_of(std::max(a.y, b.y), lo.y);
            for (long y = y0; y <= y1; ++y) {
                for (long x = x0; x <= x1; ++x) grid[y * gw + x].push_back({ri, i});
            }
        }
    }
    for (const auto& [key, list] : grid) {
        for (size_t i = 0; i < list.size(); ++i) {
            for (size_t j = i + 1; j < list.size(); ++j) {
                const SegmentRef& s = list[i];
                const SegmentRef& t = list[j];
                if (bad[s.ring] && bad[t.ring]) continue;
                Vec2 a, b, c, d;
                segment(s, a, b);
                segment(t, c, d);
                if (s.ring == t.ring) {
                    const uint32_t n = static_cast<uint32_t>(rings[s.ring].size());
                    if ((s.index + 1) % n == t.index || (t.index + 1) % n == s.index) continue;  // adjacent
                }
                if (segments_touch(a, b, c, d)) bad[s.ring] = bad[t.ring] = 1;
            }
        }
    }
}

bool point_in_ring(const Vec2& p, const std::vector<Vec2>& r) {
    bool in = false;
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
        if ((r[i].y > p.y) != (r[j].y > p.y)) {
            const double x = r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y);
            if (p.x < x) in = !in;
        }
    }
    return in;
}

// Phase 3: nesting and orientation must survive. A ring's first original
// vertex is kept by Douglas-Peucker only sometimes, so test the lowest-leftmost
// vertex, which is always kept.
void flag_nesting_changes(const std::vector<std::vector<Vec2>>& original, const std::vector<std::vector<Vec2>>& rings,
                          std::vector<uint8_t>& bad) {
    for (size_t i = 0; i < rings.size(); ++i) {
        if ((signed_area2(original[i].data(), original[i].size()) > 0.0) !=
            (signed_area2(rings[i].data(), rings[i].size()) > 0.0)) {
            bad[i] = 1;
        }
    }
    if (rings.size() < 2) return;
    for (size_t i = 0; i < rings.size(); ++i) {
        const Vec2 p = *std::min_element(rings[i].begin(), rings[i].end(), [](const Vec2& a, const Vec2& b) {
            return a.y < b.y || (a.y == b.y && a.x < b.x);
        });
        for (size_t j = 0; j < rings.size(); ++j) {
            if (j != i && point_in_ring(p, original[j]) != point_in_ring(p, rings[j])) bad[i] = bad[j] = 1;
        }
    }
}

}  // namespace

bool rings_are_simple(const std::vector<std::vector<Vec2>>& rings) {
    std::vector<uint8_t> bad(rings.size(), 0);
    flag_intersections(rings, bad);
    return std::none_of(bad.begin(), bad.end(), [](uint8_t b) { return b != 0; });
}

void simplify_rings(std::vector<std::vector<Vec2>>& rings, double tolerance) {
    if (tolerance <= 0.0 || rings.empty()) return;
    const std::vector<std::vector<Vec2>> original = rings;
    // level[i]: 0 full tolerance, 1 half, 2 unsimplified. Levels only rise, so this ends.
    std::vector<int> level(rings.size(), 0);
    for (size_t i = 0; i < rings.size(); ++i) rings[i] = simplify_ring(original[i], tolerance);
    for (int round = 0; round < 3; ++round) {
        std::vector<uint8_t> bad(rings.size(), 0);
        flag_intersections(rings, bad);
        flag_nesting_changes(original, rings, bad);
        bool any = false;
        for (size_t i = 0; i < rings.size(); ++i) {
            if (!bad[i] || level[i] == 2) continue;
            any = true;
            ++level[i];
            rings[i] = level[i] == 1 ? simplify_ring(original[i], tolerance * 0.5) : original[i];
        }
        if (!any) return;
    }
    // Anything still flagged after three rounds goes back to its original form;
    // all-original rings are valid by the input contract.
    std::vector<uint8_t> bad(rings.size(), 0);
    flag_intersections(rings, bad);
    flag_nesting_changes(original, rings, bad);
    if (std::any_of(bad.begin(), bad.end(), [](uint8_t b) { return b != 0; })) rings = original;
}

}  // namespace body
