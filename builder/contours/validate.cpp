// Contour validation and repair: finiteness, duplicate points, keyhole cuts,
// zero area, self-intersection and crossings, and even-odd nesting.
//
// References:
//   M. I. Shamos, D. Hoey, "Geometric intersection problems", FOCS 1976
//     (sweep for segment intersection; here a sort-and-sweep on x intervals).
//   W. R. Franklin, "PNPOLY - point inclusion in polygon test" (even-odd rule).
#include "builder/contours/validate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace body {
namespace {

std::string where(const std::string& path, const Contour& c) {
    return path + ": slice " + std::to_string(c.source_slice) + " contour " + std::to_string(c.source_contour);
}

std::string format_point(const Vec2& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g)", p.x, p.y);
    return buf;
}

double extent_of(std::span<const Vec2> pts) {
    Vec2 lo(1e300), hi(-1e300);
    for (const Vec2& p : pts) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return pts.empty() ? 0.0 : glm::length(hi - lo);
}

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
    return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
           p.y <= std::max(a.y, b.y);
}

// Intersection (crossing or touching) of segments ab and cd; writes the point.
bool segments_meet(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, Vec2& at) {
    double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
        double t = d1 / (d1 - d2);
        at = a + (b - a) * t;
        return true;
    }
    if (d1 == 0 && on_segment(c, d, a)) return at = a, true;
    if (d2 == 0 && on_segment(c, d, b)) return at = b, true;
    if (d3 == 0 && on_segment(a, b, c)) return at = c, true;
    if (d4 == 0 && on_segment(a, b, d)) return at = d, true;
    return false;
}

struct Segment {
    double xmin, xmax, ymin, ymax;
    uint32_t loop, index;
};

// Removes consecutive duplicates (cyclically); returns how many were removed.
size_t remove_duplicates(std::vector<Vec2>& pts) {
    size_t before = pts.size();
    std::vector<Vec2> out;
    out.reserve(pts.size());
    for (const Vec2& p : pts)
        if (out.empty() || out.back() != p) out.push_back(p);
    while (out.size() > 1 && out.back() == out.front()) out.pop_back();
    pts = std::move(out);
    return before - pts.size();
}

bool collinear(std::span<const Vec2> pts) {
    size_t far = 0;
    for (size_t i = 1; i < pts.size(); ++i)
        if (glm::length(pts[i] - pts[0]) > glm::length(pts[far] - pts[0])) far = i;
    const double len = glm::length(pts[far] - pts[0]);
    for (const Vec2& p : pts)
        if (std::abs(orient(pts[0], pts[far], p)) > 1e-12 * len * len) return false;
    return true;
}

size_t count_distinct(std::span<const Vec2> pts) {
    std::vector<Vec2> s(pts.begin(), pts.end());
    std::sort(s.begin(), s.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    return size_t(std::unique(s.begin(), s.end()) - s.begin());
}

void split_recursive(std::vector<Vec2> loop, std::vector<std::vector<Vec2>>& out, double extent) {
    const size_t n = loop.size();
    if (n < 3) return;
    std::vector<uint32_t> order(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const Vec2 &p = loop[a], &q = loop[b];
        return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && a < b)));
    });
    for (size_t k = 0; k + 1 < n; ++k) {
        if (loop[order[k]] != loop[order[k + 1]]) continue;
        size_t i = std::min(order[k], order[k + 1]), j = std::max(order[k], order[k + 1]);
        std::vector<Vec2> first(loop.begin() + long(i), loop.begin() + long(j));
        std::vector<Vec2> second(loop.begin() + long(j), loop.end());
        second.insert(second.end(), loop.begin(), loop.begin() + long(i));
        split_recursive(std::move(first), out, extent);
        split_recursive(std::move(second), out, extent);
        return;
    }
    if (std::abs(signed_area2(loop.data(), n)) <= 1e-12 * extent * extent) return;
    out.push_back(std::move(loop));
}

}  // namespace

bool point_in_polygon(const Vec2& p, std::span<const Vec2> poly) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const Vec2 &a = poly[i], &b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
    }
    return inside;
}

std::vector<std::vector<Vec2>> split_keyholes(std::span<const Vec2> points) {
    std::vector<std::vector<Vec2>> out;
    split_recursive(std::vector<Vec2>(points.begin(), points.end()), out, extent_of(points));
    return out;
}

Nesting compute_nesting(std::span<const std::span<const Vec2>> contours) {
    const size_t k = contours.size();
    Nesting n;
    n.parent.assign(k, -1);
    n.depth.assign(k, 0);
    std::vector<Vec2> lo(k, Vec2(1e300)), hi(k, Vec2(-1e300));
    for (size_t i = 0; i < k; ++i)
        for (const Vec2& p : contours[i]) lo[i] = glm::min(lo[i], p), hi[i] = glm::max(hi[i], p);
    std::vector<std::vector<int>> containers(k);
    for (size_t i = 0; i < k; ++i) {
        if (contours[i].empty()) continue;
        const Vec2 p = contours[i][0];
        for (size_t j = 0; j < k; ++j) {
            if (j == i || contours[j].size() < 3) continue;
            if (p.x < lo[j].x || p.x > hi[j].x || p.y < lo[j].y || p.y > hi[j].y) continue;
            if (point_in_polygon(p, contours[j])) containers[i].push_back(int(j));
        }
        n.depth[i] = int(containers[i].size());
    }
    for (size_t i = 0; i < k; ++i)
        for (int j : containers[i])
            if (n.depth[size_t(j)] == n.depth[i] - 1) n.parent[i] = j;
    return n;
}

Nesting compute_nesting(const Slice& slice, std::span<const uint32_t> members) {
    std::vector<std::span<const Vec2>> loops;
    for (uint32_t c : members) loops.emplace_back(slice.contours[c].points);
    return compute_nesting(loops);
}

Crossing find_crossing(std::span<const std::span<const Vec2>> loops) {
    std::vector<Segment> segs;
    for (uint32_t l = 0; l < loops.size(); ++l) {
        const auto& pts = loops[l];
        for (uint32_t i = 0; i < pts.size(); ++i) {
            const Vec2 &a = pts[i], &b = pts[(i + 1) % pts.size()];
            segs.push_back({std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y), l, i});
        }
    }
    std::sort(segs.begin(), segs.end(), [](const Segment& a, const Segment& b) { return a.xmin < b.xmin; });
    Crossing result;
    for (size_t s = 0; s < segs.size(); ++s) {
        const Segment& u = segs[s];
        const auto& lu = loops[u.loop];
        const Vec2 &a = lu[u.index], &b = lu[(u.index + 1) % lu.size()];
        for (size_t t = s + 1; t < segs.size() && segs[t].xmin <= u.xmax; ++t) {
            const Segment& v = segs[t];
            if (v.ymin > u.ymax || v.ymax < u.ymin) continue;
            const auto& lv = loops[v.loop];
            const Vec2 &c = lv[v.index], &d = lv[(v.index + 1) % lv.size()];
            Vec2 at;
            if (u.loop == v.loop) {
                const uint32_t n = uint32_t(lu.size());
                bool next = (u.index + 1) % n == v.index, prev = (v.index + 1) % n == u.index;
                if (next || prev) {
                    // Adjacent edges meet at their shared vertex; they only fail when they fold back.
                    const Vec2& shared = next ? b : a;
                    const Vec2& other_u = next ? a : b;
                    const Vec2& other_v = next ? d : c;
                    if (orient(other_u, shared, other_v) == 0 && glm::dot(other_u - shared, other_v - shared) > 0) {
                        result = {true, u.loop, v.loop, shared};
                        return result;
                    }
                    if (next && prev) continue;
                    continue;
                }
            }
            if (segments_meet(a, b, c, d, at)) {
                result = {true, std::min(u.loop, v.loop), std::max(u.loop, v.loop), at};
                return result;
            }
        }
    }
    return result;
}

Status validate_contour_stack(ContourStack& stack, const std::string& path, std::vector<std::string>& warnings) {
    for (Slice& slice : stack.slices) {
        std::vector<Contour> repaired;
        for (Contour& c : slice.contours) {
            for (size_t k = 0; k < c.points.size(); ++k)
                if (!std::isfinite(c.points[k].x) || !std::isfinite(c.points[k].y))
                    return input_error(where(path, c) + ": point " + std::to_string(k) + " is not finite");
            if (size_t removed = remove_duplicates(c.points))
                warnings.push_back(where(path, c) + ": removed " + std::to_string(removed) +
                                   " duplicate consecutive point(s)");
            if (count_distinct(c.points) < 3) return input_error(where(path, c) + ": fewer than 3 distinct points");
            const double extent = extent_of(c.points);
            if (std::abs(signed_area2(c.points.data(), c.points.size())) <= 1e-12 * extent * extent &&
                count_distinct(c.points) == c.points.size()) {
                const std::span<const Vec2> self[1] = {c.points};
                Crossing x = find_crossing(self);  // a figure eight has zero signed area too
                if (x.found && !collinear(c.points))
                    return input_error(where(path, c) + ": self-intersects at " + format_point(x.point));
                return input_error(where(path, c) + ": zero area");
            }
            if (count_distinct(c.points) == c.points.size()) {
                repaired.push_back(std::move(c));
                continue;
            }
            auto loops = split_keyholes(c.points);
            if (loops.empty()) return input_error(where(path, c) + ": zero area");
            warnings.push_back(where(path, c) + ": keyhole cut split into " + std::to_string(loops.size()) +
                               " contour(s)");
            for (auto& loop : loops) {
                Contour piece = c;
                piece.points = std::move(loop);
                repaired.push_back(std::move(piece));
            }
        }
        slice.contours = std::move(repaired);

        // Crossings within each structure group (unlabelled contours form one group).
        std::map<std::string, std::vector<size_t>> groups;
        for (size_t i = 0; i < slice.contours.size(); ++i) groups[slice.contours[i].structure].push_back(i);
        for (const auto& [id, members] : groups) {
            std::vector<std::span<const Vec2>> loops;
            for (size_t i : members) loops.emplace_back(slice.contours[i].points);
            Crossing x = find_crossing(loops);
            if (!x.found) continue;
            const Contour& a = slice.contours[members[x.loop_a]];
            const Contour& b = slice.contours[members[x.loop_b]];
            if (x.loop_a == x.loop_b)
                return input_error(where(path, a) + ": self-intersects at " + format_point(x.point));
            return input_error(where(path, a) + ": crosses slice " + std::to_string(b.source_slice) + " contour " +
                               std::to_string(b.source_contour) + " at " + format_point(x.point));
        }
    }
    return ok_status();
}

}  // namespace body
