// Material-region correspondence (contract in material_regions.h).
//
// The overlap of two regions comes by inclusion-exclusion from overlaps of whole
// contours: (A - ∪a) ∩ (B - ∪b) = A∩B - Σ A∩b - Σ a∩B + Σ a∩b for A's children
// a and B's children b (each slice's children are disjoint and inside their parent).
// A contour overlap is polygon_overlap_area where the two boundaries meet; where
// they do not, one contains the other or they are apart, which the nesting and
// one located vertex tell in O(1).
//
// Candidates: two regions overlap only if their boundaries meet (a contour pair
// that meets, or their parents) or one holds the other whole, and then it holds
// a vertex of the other's outer contour. So the pairs to sum are the meeting
// pairs with their parents, and each contour with the region of the other slice
// its first vertex lies in.
#include "builder/correspondence/material_regions.h"

#include <algorithm>
#include <cmath>

#include "builder/contours/validate.h"

namespace body {
namespace {

// One slice's nesting: depth, children, an Euler tour (for "is an ancestor"),
// contour and region areas, orientation.
struct Nest {
    NestedContours in;
    std::vector<int> depth;
    std::vector<std::vector<uint32_t>> children;
    std::vector<uint32_t> enter, leave;
    std::vector<double> area, region;
    std::vector<bool> ccw;

    explicit Nest(NestedContours c) : in(c) {
        const size_t n = c.contours.size();
        depth.assign(n, -1);
        children.resize(n);
        area.resize(n);
        ccw.resize(n);
        std::vector<uint32_t> roots;
        for (uint32_t k = 0; k < n; ++k) {
            const double a2 = signed_area2(c.contours[k].data(), c.contours[k].size());
            area[k] = std::abs(a2) / 2, ccw[k] = a2 > 0;
            (c.parent[k] >= 0 ? children[size_t(c.parent[k])] : roots).push_back(k);
        }
        region = area;
        for (uint32_t k = 0; k < n; ++k)
            if (c.parent[k] >= 0) region[size_t(c.parent[k])] -= area[k];
        enter.assign(n, 0), leave.assign(n, 0);
        uint32_t clock = 0;
        std::vector<std::pair<uint32_t, size_t>> stack;  // contour, next child
        for (uint32_t r : roots) {
            depth[r] = 0, enter[r] = clock++;
            stack.push_back({r, 0});
            while (!stack.empty()) {
                auto& [k, next] = stack.back();
                if (next < children[k].size()) {
                    const uint32_t child = children[k][next++];
                    depth[child] = depth[k] + 1, enter[child] = clock++;
                    stack.push_back({child, 0});
                } else {
                    leave[k] = clock++;
                    stack.pop_back();
                }
            }
        }
    }
    bool hole(uint32_t k) const { return depth[k] % 2 == 1; }
    int parent(uint32_t k) const { return in.parent[k]; }
    // `a` is `b` or contains it (b = -1: nothing).
    bool holds(uint32_t a, int b) const {
        return b >= 0 && enter[a] <= enter[size_t(b)] && leave[size_t(b)] <= leave[a];
    }
};

// A slice's edges bucketed in horizontal rows, for the first edge a ray to +x
// meets. Rows are at least an average edge tall, so that the edges' row
// entries stay O(E) however long some edges are.
struct RayRows {
    double y0 = 0, inv_h = 0;
    size_t count = 1;
    std::vector<uint32_t> start;
    std::vector<std::pair<uint32_t, uint32_t>> edges;  // contour, first vertex

    size_t row(double y) const {
        const double r = (y - y0) * inv_h;
        return r <= 0 ? 0 : std::min(count - 1, size_t(r));
    }

    explicit RayRows(const Nest& nest) {
        const auto& cs = nest.in.contours;
        double lo = 1e300, hi = -1e300, sum = 0;
        size_t edge_count = 0;
        for (const PolygonSpan& c : cs)
            for (size_t i = 0; i < c.size(); ++i) {
                lo = std::min(lo, c[i].y), hi = std::max(hi, c[i].y);
                sum += std::abs(c[(i + 1) % c.size()].y - c[i].y);
                ++edge_count;
            }
        if (edge_count == 0) return;
        const double height = hi - lo, mean = sum / double(edge_count);
        count = height > 0
                    ? size_t(std::clamp(height / std::max(mean, height / double(edge_count)), 1.0, double(edge_count)))
                    : 1;
        y0 = lo;
        inv_h = height > 0 ? double(count) / height : 0;
        start.assign(count + 1, 0);
        for (int pass = 0; pass < 2; ++pass) {
            std::vector<uint32_t> fill(start.begin(), start.end() - 1);
            for (uint32_t k = 0; k < cs.size(); ++k)
                for (uint32_t i = 0; i < cs[k].size(); ++i) {
                    const double ya = cs[k][i].y, yb = cs[k][(i + 1) % cs[k].size()].y;
                    for (size_t r = row(std::min(ya, yb)), last = row(std::max(ya, yb)); r <= last; ++r) {
                        if (pass == 0)
                            ++start[r + 1];
                        else
                            edges[fill[r]++] = {k, i};
                    }
                }
            if (pass == 0) {
                for (size_t r = 0; r < count; ++r) start[r + 1] += start[r];
                edges.resize(start[count]);
            }
        }
    }

    // The region (contour index, -1 outside all) of `nest` holding `p`: the
    // first edge to its right bounds it, inside that edge's contour when the
    // edge runs upwards counter-clockwise, else inside its parent.
    int locate(const Nest& nest, const Vec2& p) const {
        if (start.empty()) return -1;
        double best = 1e300;
        int found = -1;
        const size_t r = row(p.y);
        for (uint32_t e = start[r]; e < start[r + 1]; ++e) {
            const auto [k, i] = edges[e];
            const PolygonSpan c = nest.in.contours[k];
            const Vec2 a = c[i], b = c[(i + 1) % c.size()];
            if ((a.y > p.y) == (b.y > p.y)) continue;
            const double x = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
            if (x < p.x || x >= best) continue;
            best = x;
            found = (b.y > a.y) == nest.ccw[k] ? int(k) : nest.parent(k);
        }
        return found;
    }
};

struct Overlay {
    const Nest &lower, &upper;
    std::vector<uint64_t> meeting;        // lower << 32 | upper, sorted: boundaries meet
    std::vector<int> in_lower, in_upper;  // region of the other slice holding a contour's first vertex

    bool meets(uint32_t a, uint32_t b) const {
        return std::binary_search(meeting.begin(), meeting.end(), uint64_t(a) << 32 | b);
    }
    // Area of lower contour a ∩ upper contour b (whole contours).
    double overlap(uint32_t a, uint32_t b) const {
        if (meets(a, b)) return polygon_overlap_area(lower.in.contours[a], upper.in.contours[b]);
        if (lower.holds(a, in_lower[b])) return upper.area[b];
        if (upper.holds(b, in_upper[a])) return lower.area[a];
        return 0.0;
    }
    double region_overlap(uint32_t a, uint32_t b) const {
        double sum = overlap(a, b);
        for (uint32_t j : upper.children[b]) sum -= overlap(a, j);
        for (uint32_t i : lower.children[a]) {
            sum -= overlap(i, b);
            for (uint32_t j : upper.children[b]) sum += overlap(i, j);
        }
        return sum;
    }
};

Overlay make_overlay(const Nest& lower, const Nest& upper) {
    Overlay o{lower, upper, {}, {}, {}};
    const size_t n = lower.in.contours.size();
    std::vector<std::span<const Vec2>> all(lower.in.contours.begin(), lower.in.contours.end());
    all.insert(all.end(), upper.in.contours.begin(), upper.in.contours.end());
    for (const Crossing& c : find_crossings(all))
        if (c.loop_a < n && c.loop_b >= n) o.meeting.push_back(uint64_t(c.loop_a) << 32 | (c.loop_b - n));
    std::sort(o.meeting.begin(), o.meeting.end());
    const RayRows lower_rows(lower), upper_rows(upper);
    for (const PolygonSpan& c : upper.in.contours)
        o.in_lower.push_back(c.empty() ? -1 : lower_rows.locate(lower, c[0]));
    for (const PolygonSpan& c : lower.in.contours)
        o.in_upper.push_back(c.empty() ? -1 : upper_rows.locate(upper, c[0]));
    return o;
}

// Pairs whose regions may overlap (see the file comment), same kind only.
std::vector<ContourLink> candidates(const Overlay& o) {
    std::vector<ContourLink> out;
    auto add = [&](int a, int b) {
        if (a >= 0 && b >= 0 && o.lower.hole(uint32_t(a)) == o.upper.hole(uint32_t(b)))
            out.push_back({uint32_t(a), uint32_t(b)});
    };
    for (uint64_t m : o.meeting) {
        const uint32_t a = uint32_t(m >> 32), b = uint32_t(m);
        for (int x : {int(a), o.lower.parent(a)})
            for (int y : {int(b), o.upper.parent(b)}) add(x, y);
    }
    for (uint32_t b = 0; b < o.in_lower.size(); ++b) add(o.in_lower[b], int(b));
    for (uint32_t a = 0; a < o.in_upper.size(); ++a) add(int(a), o.in_upper[a]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The thesis method on whole contours, solids with solids and holes with holes.
std::vector<ContourLink> by_kind(const Nest& lower, const Nest& upper, CorrespondenceMethod method) {
    std::vector<ContourLink> out;
    for (int hole = 0; hole < 2; ++hole) {
        std::vector<uint32_t> lo, up;
        std::vector<PolygonSpan> a, b;
        for (uint32_t k = 0; k < lower.depth.size(); ++k)
            if (lower.hole(k) == bool(hole)) lo.push_back(k), a.push_back(lower.in.contours[k]);
        for (uint32_t k = 0; k < upper.depth.size(); ++k)
            if (upper.hole(k) == bool(hole)) up.push_back(k), b.push_back(upper.in.contours[k]);
        if (lo.empty() || up.empty()) continue;
        for (const ContourLink& l : correspond_contours(a, b, method)) out.push_back({lo[l.lower], up[l.upper]});
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

std::vector<RegionOverlap> region_overlaps(NestedContours lower, NestedContours upper) {
    const Nest lo(lower), up(upper);
    const Overlay o = make_overlay(lo, up);
    std::vector<RegionOverlap> out;
    for (const ContourLink& l : candidates(o)) {
        const double area = o.region_overlap(l.lower, l.upper);
        if (area > 1e-9 * std::max(0.0, std::min(lo.region[l.lower], up.region[l.upper]))) out.push_back({l, area});
    }
    return out;
}

std::vector<ContourLink> correspond_nested(NestedContours lower, NestedContours upper, CorrespondenceMethod method) {
    if (method != CorrespondenceMethod::Overlap) return by_kind(Nest(lower), Nest(upper), method);
    std::vector<ContourLink> links;
    for (const RegionOverlap& r : region_overlaps(lower, upper)) links.push_back(r.link);
    return links;
}

}  // namespace body
