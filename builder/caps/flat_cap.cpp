// Flat caps: ear clipping of a polygon with holes, each hole first bridged to
// the outer boundary through a mutually visible vertex pair.
//
// References:
//   D. Eberly, "Triangulation by Ear Clipping", Geometric Tools, 2002-2015
//     (hole bridging: rightmost hole vertex, ray cast, reflex-vertex visibility).
//   G. H. Meisters, "Polygons have ears", Amer. Math. Monthly 82, 1975.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <unordered_map>

#include "builder/caps/boundary_distance.h"
#include "builder/caps/caps.h"
#include "builder/caps/dome_groups.h"
#include "builder/caps/monotone_cap.h"

namespace body {
namespace {

struct Vert {
    Vec2 p;
    uint32_t id;  // index into the concatenated loops
};

double cross3(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// A strictly convex corner: collinear points (traced outlines are full of
// them) never make an ear, so no triangle is flat.
bool strictly_convex(const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross3(a, b, c) > 1e-10 * glm::length(b - a) * glm::length(c - b);
}

bool in_triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& p) {
    return cross3(a, b, p) >= 0 && cross3(b, c, p) >= 0 && cross3(c, a, p) >= 0;
}

// Loop k as vertices in the wanted orientation (ccw for the outer boundary, cw for holes).
std::vector<Vert> oriented_loop(std::span<const Vec2> loop, uint32_t first_id, bool ccw) {
    std::vector<Vert> out(loop.size());
    for (size_t i = 0; i < loop.size(); ++i) out[i] = {loop[i], first_id + uint32_t(i)};
    if ((signed_area2(loop.data(), loop.size()) > 0) != ccw) std::reverse(out.begin(), out.end());
    return out;
}

// Joins `hole` (clockwise) into `outer` (counter-clockwise) through a visible pair.
void bridge_hole(std::vector<Vert>& outer, const std::vector<Vert>& hole) {
    size_t mi = 0;
    for (size_t i = 1; i < hole.size(); ++i)
        if (hole[i].p.x > hole[mi].p.x) mi = i;
    const Vec2 M = hole[mi].p;
    // Closest edge hit by the ray from M towards +x.
    double best_x = 1e300;
    size_t best_edge = SIZE_MAX;
    const size_t n = outer.size();
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = outer[i].p, b = outer[(i + 1) % n].p;
        if ((a.y > M.y) == (b.y > M.y) && a.y != M.y && b.y != M.y) continue;
        if (a.y == b.y) {
            if (a.y != M.y) continue;
            const double x = std::min(a.x, b.x);
            if (x >= M.x && x < best_x) best_x = x, best_edge = i;
            continue;
        }
        const double t = (M.y - a.y) / (b.y - a.y);
        if (t < 0 || t > 1) continue;
        const double x = a.x + t * (b.x - a.x);
        if (x >= M.x && x < best_x) best_x = x, best_edge = i;
    }
    size_t vi = 0;
    if (best_edge == SIZE_MAX) {
        // Should not happen for a hole inside the outer loop; fall back to the closest vertex.
        double best = 1e300;
        for (size_t i = 0; i < n; ++i) {
            const double d = glm::length(outer[i].p - M);
            if (d < best) best = d, vi = i;
        }
    } else {
        const Vec2 I(best_x, M.y);
        const size_t a = best_edge, b = (best_edge + 1) % n;
        vi = outer[a].p.x > outer[b].p.x ? a : b;
        if (outer[a].p == I) vi = a;
        if (outer[b].p == I) vi = b;
        if (outer[vi].p != I) {
            // Reflex vertices inside triangle (M, I, P) may block the view; take the one closest in angle.
            const Vec2 P = outer[vi].p;
            double best_angle = 1e300, best_dist = 1e300;
            for (size_t i = 0; i < n; ++i) {
                const Vec2 prev = outer[(i + n - 1) % n].p, cur = outer[i].p, next = outer[(i + 1) % n].p;
                if (cross3(prev, cur, next) > 0 || i == vi) continue;  // convex vertices cannot block
                const bool inside =
                    cur.x >= M.x && (cross3(M, I, P) >= 0 ? in_triangle(M, I, P, cur) : in_triangle(M, P, I, cur));
                if (!inside) continue;
                const Vec2 d = cur - M;
                const double angle = std::atan2(std::abs(d.y), d.x), dist = glm::length(d);
                if (angle < best_angle || (angle == best_angle && dist < best_dist))
                    best_angle = angle, best_dist = dist, vi = i;
            }
        }
    }
    // A vertex already used by an earlier bridge appears twice: take the copy
    // whose interior wedge holds M, or the new bridge would cross the old one.
    for (size_t k = 0; k < n; ++k) {
        if (outer[k].p != outer[vi].p) continue;
        const Vec2 prev = outer[(k + n - 1) % n].p, cur = outer[k].p, next = outer[(k + 1) % n].p;
        const bool convex = cross3(prev, cur, next) > 0;
        const bool left_in = cross3(prev, cur, M) >= 0, left_out = cross3(cur, next, M) >= 0;
        if (convex ? (left_in && left_out) : (left_in || left_out)) {
            vi = k;
            break;
        }
    }
    std::vector<Vert> merged;
    merged.reserve(n + hole.size() + 2);
    merged.insert(merged.end(), outer.begin(), outer.begin() + long(vi) + 1);
    for (size_t k = 0; k <= hole.size(); ++k) merged.push_back(hole[(mi + k) % hole.size()]);
    merged.push_back(outer[vi]);
    merged.insert(merged.end(), outer.begin() + long(vi) + 1, outer.end());
    outer = std::move(merged);
}

bool is_ear(const std::vector<Vert>& poly, const std::vector<uint32_t>& prev, const std::vector<uint32_t>& next,
            uint32_t i, uint32_t count) {
    const Vec2 a = poly[prev[i]].p, b = poly[i].p, c = poly[next[i]].p;
    if (!strictly_convex(a, b, c)) return false;
    uint32_t k = next[next[i]];
    for (uint32_t s = 0; s + 3 < count; ++s, k = next[k]) {
        const Vec2 p = poly[k].p;
        if (p == a || p == b || p == c) continue;
        if (in_triangle(a, b, c, p)) return false;
    }
    return true;
}

bool flat(const Vec2& a, const Vec2& b, const Vec2& c) {
    const double scale = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    return std::abs(cross3(a, b, c)) <= 1e-10 * scale * scale;
}

// Collinear points left at the end of a triangulation make a flat triangle
// (u, w, m) with m between u and w. The triangle (w, u, x) across its long
// edge is replaced, together with it, by (w, m, x) and (m, u, x): the same
// area, the same boundary, nothing flat (Lawson-style edge flip). A flip never
// makes a flat triangle, so passes repeat only while some flip succeeds; each
// pass is one scan of the triangles against a hash of the long edges wanted.
Status flip_flat_triangles(const std::vector<Vec2>& at, std::vector<uint32_t>& tris, size_t begin) {
    auto key = [](uint32_t a, uint32_t b) { return (uint64_t(a) << 32) | b; };
    std::vector<size_t> flats;
    for (size_t t = begin; t < tris.size(); t += 3)
        if (flat(at[tris[t]], at[tris[t + 1]], at[tris[t + 2]])) flats.push_back(t);
    std::unordered_map<uint64_t, size_t> across;  // long edge (w, u) reversed -> triangle holding it
    std::vector<uint8_t> touched((tris.size() - begin) / 3, 0);
    for (int pass = 0; pass < 64 && !flats.empty(); ++pass) {
        struct Flat {
            size_t t;
            uint32_t m, u, w;
        };
        std::vector<Flat> wanted;
        across.clear();
        for (size_t t : flats) {
            const uint32_t* v = &tris[t];
            // m: the vertex between the other two (the long edge is opposite it).
            int mk = 0;
            double longest = -1;
            for (int k = 0; k < 3; ++k) {
                const double len = glm::length(at[v[(k + 1) % 3]] - at[v[(k + 2) % 3]]);
                if (len > longest) longest = len, mk = k;
            }
            wanted.push_back({t, v[mk], v[(mk + 1) % 3], v[(mk + 2) % 3]});
            across.emplace(key(v[(mk + 2) % 3], v[(mk + 1) % 3]), SIZE_MAX);
        }
        for (size_t t = begin; t < tris.size(); t += 3)
            for (int k = 0; k < 3; ++k)
                if (auto it = across.find(key(tris[t + k], tris[t + (k + 1) % 3])); it != across.end()) it->second = t;
        std::fill(touched.begin(), touched.end(), uint8_t(0));
        std::vector<size_t> left;
        for (const Flat& f : wanted) {
            const size_t o = across[key(f.w, f.u)];
            if (o == SIZE_MAX || o == f.t || touched[(f.t - begin) / 3] || touched[(o - begin) / 3]) {
                left.push_back(f.t);
                continue;
            }
            const uint32_t* q = &tris[o];
            const uint32_t x = q[0] + q[1] + q[2] - f.w - f.u;  // the third vertex of (w, u, x)
            if (flat(at[f.w], at[f.m], at[x]) || flat(at[f.m], at[f.u], at[x])) {
                left.push_back(f.t);
                continue;
            }
            tris[f.t] = f.w, tris[f.t + 1] = f.m, tris[f.t + 2] = x;
            tris[o] = f.m, tris[o + 1] = f.u, tris[o + 2] = x;
            touched[(f.t - begin) / 3] = touched[(o - begin) / 3] = 1;
        }
        if (left.size() == flats.size()) break;
        flats = std::move(left);
    }
    // A flat triangle that no flip removes (its long edge on the boundary: a
    // vertex touching another loop) stays; the cap is still closed.
    return ok_status();
}

constexpr size_t kEarClippingLimit = 4096;
Status ear_clip(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles);

}  // namespace

const char* cap_style_name(CapStyle style) {
    switch (style) {
        case CapStyle::Flat: return "flat";
        case CapStyle::Dome: return "dome";
        case CapStyle::None: return "none";
    }
    return "?";
}

Status triangulate_polygon_with_holes(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles) {
    if (loops.empty() || loops[0].size() < 3) return input_error("cap: outer loop has fewer than 3 points");
    size_t total = 0;
    for (const auto& loop : loops) total += loop.size();
    // Small regions: ear clipping (quadratic, but its ears are better shaped
    // than the sweep's fans, and it copes with touching loops). Large ones:
    // the O(n log n) sweep.
    if (total <= kEarClippingLimit) return ear_clip(loops, triangles);
    std::vector<Vec2> at;
    at.reserve(total);
    for (const auto& loop : loops) at.insert(at.end(), loop.begin(), loop.end());
    const size_t begin = triangles.size();
    if (triangulate_monotone(loops, triangles)) return flip_flat_triangles(at, triangles, begin);
    triangles.resize(begin);
    return input_error("cap: region of " + std::to_string(total) + " points has touching or crossing loops");
}

namespace {

Status ear_clip(std::span<const std::span<const Vec2>> loops, std::vector<uint32_t>& triangles) {
    const size_t triangles_begin = triangles.size();
    uint32_t first = uint32_t(loops[0].size());
    std::vector<Vert> poly = oriented_loop(loops[0], 0, true);
    std::vector<std::vector<Vert>> holes;
    for (size_t k = 1; k < loops.size(); ++k) {
        holes.push_back(oriented_loop(loops[k], first, false));
        first += uint32_t(loops[k].size());
    }
    std::sort(holes.begin(), holes.end(), [](const std::vector<Vert>& a, const std::vector<Vert>& b) {
        auto mx = [](const std::vector<Vert>& h) {
            double x = -1e300;
            for (const Vert& v : h) x = std::max(x, v.p.x);
            return x;
        };
        return mx(a) > mx(b);
    });
    for (const auto& h : holes) bridge_hole(poly, h);

    const uint32_t n = uint32_t(poly.size());
    std::vector<uint32_t> prev(n), next(n);
    for (uint32_t i = 0; i < n; ++i) prev[i] = (i + n - 1) % n, next[i] = (i + 1) % n;
    uint32_t count = n, i = 0, misses = 0;
    while (count > 3) {
        if (is_ear(poly, prev, next, i, count)) {
            triangles.insert(triangles.end(), {poly[prev[i]].id, poly[i].id, poly[next[i]].id});
            next[prev[i]] = next[i];
            prev[next[i]] = prev[i];
            --count;
            i = prev[i];
            misses = 0;
            continue;
        }
        i = next[i];
        if (++misses <= count) continue;
        // No clean ear (numerical trouble): clip the most convex vertex.
        uint32_t best = UINT32_MAX, k = i;
        double best_cross = 0;
        for (uint32_t s = 0; s < count; ++s, k = next[k]) {
            const double c = cross3(poly[prev[k]].p, poly[k].p, poly[next[k]].p);
            if (c > best_cross && strictly_convex(poly[prev[k]].p, poly[k].p, poly[next[k]].p))
                best_cross = c, best = k;
        }
        if (best == UINT32_MAX) {
            // Only collinear or reflex corners left: clip the flattest one; the
            // flat triangle is flipped away below.
            double flattest = -1e300;
            for (uint32_t s2 = 0; s2 < count; ++s2, k = next[k]) {
                const double c = cross3(poly[prev[k]].p, poly[k].p, poly[next[k]].p);
                if (c > flattest) flattest = c, best = k;
            }
            if (!(flattest >= -1e-10 * glm::length(poly[best].p - poly[prev[best]].p) *
                                  glm::length(poly[next[best]].p - poly[best].p)))
                return input_error("cap: region has no convex vertex left (zero area?)");
        }
        triangles.insert(triangles.end(), {poly[prev[best]].id, poly[best].id, poly[next[best]].id});
        next[prev[best]] = next[best];
        prev[next[best]] = prev[best];
        --count;
        i = prev[best];
        misses = 0;
    }
    triangles.insert(triangles.end(), {poly[prev[i]].id, poly[i].id, poly[next[i]].id});
    std::vector<Vec2> at(first);
    for (const Vert& v : poly) at[v.id] = v.p;
    return flip_flat_triangles(at, triangles, triangles_begin);
}

}  // namespace

Status build_cap(std::span<const std::span<const Vec2>> loops, std::span<const std::span<const uint32_t>> ids, double z,
                 bool up, CapStyle style, double dome_height, std::vector<Vec3>& positions,
                 std::vector<uint32_t>& triangles, bool tip, bool lift_chords) {
    if (style == CapStyle::None) return ok_status();
    std::vector<uint32_t> local;
    auto status = triangulate_polygon_with_holes(loops, local);
    if (!status) return status;
    std::vector<uint32_t> global;  // concatenated ids
    std::vector<Vec2> flat;        // concatenated points
    for (size_t k = 0; k < loops.size(); ++k) {
        global.insert(global.end(), ids[k].begin(), ids[k].end());
        flat.insert(flat.end(), loops[k].begin(), loops[k].end());
    }
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (up)
            triangles.insert(triangles.end(), {a, b, c});
        else
            triangles.insert(triangles.end(), {a, c, b});
    };
    if (style == CapStyle::Flat) {
        for (size_t t = 0; t < local.size(); t += 3) emit(global[local[t]], global[local[t + 1]], global[local[t + 2]]);
        return ok_status();
    }
    // Dome: a height field over the flat cap, sampled at one apex per group of
    // cap triangles (dome_groups.h), lifted by a height that grows with its
    // distance to the boundary; each group becomes a fan around its apex, so
    // the dome cannot fold onto itself.
    std::vector<DomeGroup> groups;
    std::vector<uint32_t> cycles;
    dome_groups(flat, local, groups, cycles);
    const BoundaryDistance distance(loops);
    std::vector<double> dist(groups.size(), 0.0);
    double dmax = 0;
    for (size_t g = 0; g < groups.size(); ++g) {
        dist[g] = distance(groups[g].apex);
        dmax = std::max(dmax, dist[g]);
    }
    const auto lift = [&](const Vec2& p) {
        const double u = dmax > 0 ? std::min(1.0, distance(p) / dmax) : 0.0;
        const double h = dome_height * (tip ? u * (2 - u) : std::sqrt(u));
        return Vec3(p, z + (up ? h : -h));
    };
    lift_groups(groups, cycles, global, lift, positions, emit, flat, lift_chords ? 0.5 * dmax : 0.0);
    return ok_status();
}

}  // namespace body
