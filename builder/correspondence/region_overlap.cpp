// Region-overlap correspondence: contours on adjacent slices are linked when
// the regions they bound overlap (a 2-D boolean overlay of the two slices).
//
// References:
//   E. Keppel, "Approximating complex surfaces by triangulation of contour
//     lines", IBM J. Res. Dev. 19(1), 1975 (overlap as the correspondence cue).
//   K. Soroka, "Generalized cones from serial sections", CGIP 15, 1981.
//   Area of intersection via Green's theorem: the boundary of A∩B is the part
//   of ∂A inside B plus the part of ∂B inside A.
#include <algorithm>
#include <cmath>

#include "builder/correspondence/correspondence.h"

namespace body {
namespace {

struct Box {
    Vec2 lo{1e300}, hi{-1e300};
};

Box box_of(PolygonSpan p) {
    Box b;
    for (const Vec2& v : p) b.lo = glm::min(b.lo, v), b.hi = glm::max(b.hi, v);
    return b;
}

bool boxes_overlap(const Box& a, const Box& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}

double cross2(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

// Vertex k of `p` traversed counter-clockwise.
Vec2 ccw_vertex(PolygonSpan p, bool reversed, size_t k) { return reversed ? p[p.size() - 1 - k] : p[k]; }

// b's edges bucketed by the horizontal rows their y-range (padded by tol)
// touches, so that crossings and the even-odd ray only visit nearby edges.
struct EdgeRows {
    double y0 = 0, inv_h = 0;
    size_t count = 1;
    std::vector<uint32_t> start, edges;  // CSR: row r holds edges[start[r] .. start[r+1])

    size_t row(double y) const {
        const double r = (y - y0) * inv_h;
        return r <= 0 ? 0 : std::min(count - 1, size_t(r));
    }

    EdgeRows(PolygonSpan b, const Box& box, double tol) {
        const size_t m = b.size();
        count = std::max<size_t>(1, m / 2);
        y0 = box.lo.y - tol;
        const double h = (box.hi.y + tol - y0) / double(count);
        inv_h = h > 0 ? 1 / h : 0;
        start.assign(count + 1, 0);
        for (int pass = 0; pass < 2; ++pass) {
            std::vector<uint32_t> fill(start.begin(), start.end() - 1);
            for (uint32_t j = 0; j < m; ++j) {
                const double ya = b[j].y, yb = b[(j + 1) % m].y;
                for (size_t r = row(std::min(ya, yb) - tol), last = row(std::max(ya, yb) + tol); r <= last; ++r) {
                    if (pass == 0)
                        ++start[r + 1];
                    else
                        edges[fill[r]++] = j;
                }
            }
            if (pass == 0) {
                for (size_t r = 0; r < count; ++r) start[r + 1] += start[r];
                edges.resize(start[count]);
            }
        }
    }
};

// Twice the integral of x dy - y dx over the part of ∂a (taken counter-clockwise)
// inside b. Boundary shared with b counts only when `count_shared` and both run the same way.
double boundary_inside(PolygonSpan a, bool a_rev, PolygonSpan b, bool b_rev, const Box& bbox, double tol,
                       bool count_shared) {
    const size_t n = a.size(), m = b.size();
    const EdgeRows rows(b, bbox, tol);
    std::vector<double> ts;
    double sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const Vec2 p = ccw_vertex(a, a_rev, i), q = ccw_vertex(a, a_rev, (i + 1) % n);
        const Vec2 lo = glm::min(p, q), hi = glm::max(p, q);
        if (hi.x < bbox.lo.x - tol || lo.x > bbox.hi.x + tol || hi.y < bbox.lo.y - tol || lo.y > bbox.hi.y + tol)
            continue;  // edge entirely outside b
        const Vec2 pq = q - p;
        const double len2 = glm::dot(pq, pq);
        if (len2 == 0) continue;
        ts.assign({0.0, 1.0});
        for (size_t r = rows.row(lo.y - tol), last = rows.row(hi.y + tol); r <= last; ++r)
            for (uint32_t e = rows.start[r]; e < rows.start[r + 1]; ++e) {
                const uint32_t j = rows.edges[e];
                const Vec2 c = b[j], d = b[(j + 1) % m];
                if (std::max(c.x, d.x) < lo.x - tol || std::min(c.x, d.x) > hi.x + tol ||
                    std::max(c.y, d.y) < lo.y - tol || std::min(c.y, d.y) > hi.y + tol)
                    continue;
                const Vec2 cd = d - c;
                const double den = cross2(pq, cd);
                if (den != 0) {
                    const double t = cross2(c - p, cd) / den, u = cross2(c - p, pq) / den;
                    if (t > 0 && t < 1 && u >= 0 && u <= 1) ts.push_back(t);
                }
                // b's vertices lying on pq (touching or collinear overlap).
                const double tc = glm::dot(c - p, pq) / len2;
                if (tc > 0 && tc < 1 && glm::length(p + pq * tc - c) <= tol) ts.push_back(tc);
            }
        std::sort(ts.begin(), ts.end());
        for (size_t k = 0; k + 1 < ts.size(); ++k) {
            if (ts[k + 1] - ts[k] <= 1e-14) continue;
            const Vec2 s0 = p + pq * ts[k], s1 = p + pq * ts[k + 1], mid = (s0 + s1) * 0.5;
            // Classify mid against b: inside (even-odd), or on b's boundary. Every
            // edge spanning mid.y (and every edge within tol of mid) is in mid's row.
            bool inside = false, on = false, same_way = false;
            const size_t r = rows.row(mid.y);
            for (uint32_t e = rows.start[r]; e < rows.start[r + 1]; ++e) {
                const uint32_t j = rows.edges[e];
                const Vec2 &u = b[(j + 1) % m], &v = b[j];
                if ((u.y > mid.y) != (v.y > mid.y) && mid.x < (v.x - u.x) * (mid.y - u.y) / (v.y - u.y) + u.x)
                    inside = !inside;
                const Vec2 uv = v - u;
                const double l2 = glm::dot(uv, uv);
                const double t = l2 > 0 ? std::clamp(glm::dot(mid - u, uv) / l2, 0.0, 1.0) : 0.0;
                if (!on && glm::length(u + uv * t - mid) <= tol) {
                    on = true;
                    // b's edge j -> j+1 runs v -> u in storage order; counter-clockwise direction:
                    const Vec2 dir = b_rev ? (v - u) : (u - v);
                    same_way = glm::dot(dir, pq) > 0;
                }
            }
            if (on ? (count_shared && same_way) : inside) sum += cross2(s0, s1);
        }
    }
    return sum;
}

}  // namespace

double polygon_overlap_area(PolygonSpan a, PolygonSpan b) {
    if (a.size() < 3 || b.size() < 3) return 0.0;
    const Box ba = box_of(a), bb = box_of(b);
    if (!boxes_overlap(ba, bb)) return 0.0;
    const double extent = std::max(glm::length(ba.hi - ba.lo), glm::length(bb.hi - bb.lo));
    const double tol = 1e-10 * extent;
    const bool a_rev = signed_area2(a.data(), a.size()) < 0, b_rev = signed_area2(b.data(), b.size()) < 0;
    const double twice =
        boundary_inside(a, a_rev, b, b_rev, bb, tol, true) + boundary_inside(b, b_rev, a, a_rev, ba, tol, false);
    return std::max(0.0, twice * 0.5);
}

std::vector<ContourLink> correspond_by_overlap(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper) {
    std::vector<ContourLink> links;
    std::vector<double> area_lower(lower.size()), area_upper(upper.size());
    for (size_t i = 0; i < lower.size(); ++i)
        area_lower[i] = std::abs(signed_area2(lower[i].data(), lower[i].size())) / 2;
    for (size_t j = 0; j < upper.size(); ++j)
        area_upper[j] = std::abs(signed_area2(upper[j].data(), upper[j].size())) / 2;
    std::vector<Box> box_upper(upper.size());
    for (size_t j = 0; j < upper.size(); ++j) box_upper[j] = box_of(upper[j]);
    for (uint32_t i = 0; i < lower.size(); ++i) {
        const Box box_lower = box_of(lower[i]);
        for (uint32_t j = 0; j < upper.size(); ++j) {
            if (!boxes_overlap(box_lower, box_upper[j])) continue;  // cheap for many small contours
            const double overlap = polygon_overlap_area(lower[i], upper[j]);
            if (overlap > 1e-9 * std::min(area_lower[i], area_upper[j])) links.push_back({i, j});
        }
    }
    return links;
}

const char* correspondence_method_name(CorrespondenceMethod method) {
    return method == CorrespondenceMethod::Overlap ? "overlap" : "ellipse";
}

std::vector<ContourLink> correspond_contours(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper,
                                             CorrespondenceMethod method) {
    auto links = method == CorrespondenceMethod::Overlap ? correspond_by_overlap(lower, upper)
                                                         : correspond_by_ellipse(lower, upper);
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
    return links;
}

}  // namespace body
