// Triangle-mesh self-intersection count.
//
// References:
// - T. Möller, "A fast triangle-triangle intersection test", JGT 2(2), 1997:
//   two non-coplanar triangles meet iff an edge of one crosses the other,
//   decided here with orientation (signed volume) predicates.
// - P. Guigue, O. Devillers, "Fast and robust triangle-triangle overlap test
//   using orientation predicates", JGT 8(1), 2003 (the coplanar case in 2-D).
// - Uniform-grid broad phase with the "lowest shared cell" rule so that each
//   pair is tested once (Ericson, Real-Time Collision Detection, 7.1).
#include "shared/mesh_intersect.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "shared/mesh.h"

namespace body {

namespace {

// Orientation predicates with a tolerance: values within eps count as zero.
struct Predicates {
    double eps3;  // for signed volumes (length^3)
    double eps2;  // for 2-D cross products (length^2)

    int sign3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) const {
        double v = glm::dot(glm::cross(b - a, c - a), d - a);
        return v > eps3 ? 1 : (v < -eps3 ? -1 : 0);
    }
    int sign2(const Vec2& a, const Vec2& b, const Vec2& c) const {
        double v = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        return v > eps2 ? 1 : (v < -eps2 ? -1 : 0);
    }
};

// Segment pq against triangle abc (p, q not both in its plane).
static bool segment_crosses_triangle(const Predicates& pr, const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                                     const Vec3& c) {
    int sp = pr.sign3(a, b, c, p), sq = pr.sign3(a, b, c, q);
    if (sp == sq) return false;  // same side, or both in the plane (coplanar case elsewhere)
    int s1 = pr.sign3(p, q, a, b), s2 = pr.sign3(p, q, b, c), s3 = pr.sign3(p, q, c, a);
    bool has_neg = s1 < 0 || s2 < 0 || s3<0, has_pos = s1> 0 || s2 > 0 || s3 > 0;
    return !(has_neg && has_pos);
}

static bool segments_cross_2d(const Predicates& pr, const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    int o1 = pr.sign2(a, b, c), o2 = pr.sign2(a, b, d), o3 = pr.sign2(c, d, a), o4 = pr.sign2(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    auto on = [](const Vec2& p, const Vec2& q, const Vec2& r) {  // r on segment pq, given collinear
        return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
               r.y <= std::max(p.y, q.y);
    };
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) || (o4 == 0 && on(c, d, b));
}

static bool point_in_triangle_2d(const Predicates& pr, const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    int s1 = pr.sign2(a, b, p), s2 = pr.sign2(b, c, p), s3 = pr.sign2(c, a, p);
    bool has_neg = s1 < 0 || s2 < 0 || s3<0, has_pos = s1> 0 || s2 > 0 || s3 > 0;
    return !(has_neg && has_pos);
}

// Drops the coordinate along the normal's largest component.
static std::array<Vec2, 6> project(const Vec3& n, std::span<const Vec3, 6> v) {
    Vec3 a = glm::abs(n);
    int drop = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    std::array<Vec2, 6> out;
    for (int k = 0; k < 6; ++k)
        out[k] = drop == 0 ? Vec2(v[k].y, v[k].z) : (drop == 1 ? Vec2(v[k].z, v[k].x) : Vec2(v[k].x, v[k].y));
    return out;
}

static bool coplanar_overlap(const Predicates& pr, const Vec3& n, std::span<const Vec3, 6> v) {
    auto p = project(n, v);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (segments_cross_2d(pr, p[i], p[(i + 1) % 3], p[3 + j], p[3 + (j + 1) % 3])) return true;
    return point_in_triangle_2d(pr, p[0], p[3], p[4], p[5]) || point_in_triangle_2d(pr, p[3], p[0], p[1], p[2]);
}

static bool is_coplanar(const Predicates& pr, const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2) {
    return pr.sign3(a0, a1, a2, b0) == 0 && pr.sign3(a0, a1, a2, b1) == 0 && pr.sign3(a0, a1, a2, b2) == 0;
}

static bool disjoint_intersect(const Predicates& pr, const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                               const Vec3& b1, const Vec3& b2) {
    if (is_coplanar(pr, a0, a1, a2, b0, b1, b2)) {
        const Vec3 v[6] = {a0, a1, a2, b0, b1, b2};
        return coplanar_overlap(pr, glm::cross(a1 - a0, a2 - a0), std::span<const Vec3, 6>(v));
    }
    return segment_crosses_triangle(pr, a0, a1, b0, b1, b2) || segment_crosses_triangle(pr, a1, a2, b0, b1, b2) ||
           segment_crosses_triangle(pr, a2, a0, b0, b1, b2) || segment_crosses_triangle(pr, b0, b1, a0, a1, a2) ||
           segment_crosses_triangle(pr, b1, b2, a0, a1, a2) || segment_crosses_triangle(pr, b2, b0, a0, a1, a2);
}

// Triangles (v, a, b) and (v, c, d) sharing vertex v: do they meet elsewhere?
static bool vertex_adjacent_intersect(const Predicates& pr, const Vec3& v, const Vec3& a, const Vec3& b, const Vec3& c,
                                      const Vec3& d) {
    Vec3 n1 = glm::cross(a - v, b - v), n2 = glm::cross(c - v, d - v);
    if (is_coplanar(pr, v, a, b, v, c, d)) {
        // Both lie in their wedges at v; they overlap iff the wedges do.
        const Vec3 pts[6] = {v, a, b, v, c, d};
        auto p = project(n1, std::span<const Vec3, 6>(pts));
        auto inside = [&](const Vec2& q, const Vec2& o, const Vec2& e1, const Vec2& e2) {  // strictly in wedge
            int s = pr.sign2(o, e1, e2);
            return pr.sign2(o, e1, q) == s && pr.sign2(o, q, e2) == s && s != 0;
        };
        auto same_dir = [&](const Vec2& o, const Vec2& e, const Vec2& f) {
            return pr.sign2(o, e, f) == 0 && glm::dot(e - o, f - o) > 0;
        };
        if (inside(p[4], p[0], p[1], p[2]) || inside(p[5], p[0], p[1], p[2]) || inside(p[1], p[0], p[4], p[5]) ||
            inside(p[2], p[0], p[4], p[5]))
            return true;
        // Coincident wedges, or edges along the same ray (touching along an edge).
        return same_dir(p[0], p[1], p[4]) || same_dir(p[0], p[1], p[5]) || same_dir(p[0], p[2], p[4]) ||
               same_dir(p[0], p[2], p[5]);
    }
    // Each triangle meets the other's plane in a segment from v (or only in v);
    // they meet elsewhere iff both segments leave v on the same side.
    auto segment_end = [&](const Vec3& p, const Vec3& q, const Vec3& n, bool& ok) {
        double dp = glm::dot(n, p - v), dq = glm::dot(n, q - v);
        double tol = pr.eps3;
        int sp = dp > tol ? 1 : (dp < -tol ? -1 : 0), sq = dq > tol ? 1 : (dq < -tol ? -1 : 0);
        ok = !(sp == sq && sp != 0);
        if (sp == 0 && sq == 0) return (p + q) * 0.5 - v;  // edge in the plane: any point of it
        if (sp == 0) return p - v;
        if (sq == 0) return q - v;
        double t = dp / (dp - dq);
        return p + t * (q - p) - v;
    };
    bool ok1, ok2;
    Vec3 e1 = segment_end(a, b, n2, ok1), e2 = segment_end(c, d, n1, ok2);
    if (!ok1 || !ok2) return false;
    Vec3 line = glm::cross(n1, n2);
    double s1 = glm::dot(e1, line), s2 = glm::dot(e2, line);
    double tol = pr.eps3 * 1e-3 * glm::length(line);
    return (s1 > tol && s2 > tol) || (s1 < -tol && s2 < -tol);
}

// Triangles (u, v, a) and (v, u, b) sharing edge uv: they meet beyond it only
// when coplanar with a and b on the same side (folded onto each other).
static bool edge_adjacent_intersect(const Predicates& pr, const Vec3& u, const Vec3& v, const Vec3& a, const Vec3& b) {
    if (pr.sign3(u, v, a, b) != 0) return false;
    Vec3 n = glm::cross(v - u, a - u);
    double sa = glm::dot(glm::cross(v - u, a - u), n), sb = glm::dot(glm::cross(v - u, b - u), n);
    return sa * sb > 0;
}

struct Grid {
    Vec3 origin;
    double cell = 1;
    int dims[3] = {1, 1, 1};
    void cell_of(const Vec3& p, int out[3]) const {
        for (int k = 0; k < 3; ++k) out[k] = std::clamp(int(std::floor((p[k] - origin[k]) / cell)), 0, dims[k] - 1);
    }
    uint64_t key(int x, int y, int z) const { return (uint64_t(z) * uint64_t(dims[1]) + uint64_t(y)) * dims[0] + x; }
};

// Phase 1: cell size from the mean triangle box so that a triangle spans few cells.
static Grid make_grid(const Aabb& bounds, double mean_extent, size_t triangles) {
    Grid g;
    g.origin = bounds.min;
    Vec3 size = bounds.size();
    double cell = std::max(mean_extent, 1e-300);
    double volume_cell = std::cbrt(std::max(size.x, cell) * std::max(size.y, cell) * std::max(size.z, cell) /
                                   double(std::max<size_t>(triangles, 1)));
    cell = std::max(cell, volume_cell);
    for (int k = 0; k < 3; ++k) g.dims[k] = std::clamp(int(size[k] / cell) + 1, 1, 1 << 20);
    // Keep the key space representable.
    while (double(g.dims[0]) * g.dims[1] * g.dims[2] > 1e15) {
        cell *= 2;
        for (int k = 0; k < 3; ++k) g.dims[k] = std::clamp(int(size[k] / cell) + 1, 1, 1 << 20);
    }
    g.cell = cell;
    return g;
}

}  // namespace

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2) {
    Aabb box;
    for (const Vec3* p : {&a0, &a1, &a2, &b0, &b1, &b2}) box.extend(*p);
    double scale = std::max(box.extent(), 1e-300);
    Predicates pr{1e-12 * scale * scale * scale, 1e-12 * scale * scale};
    return disjoint_intersect(pr, a0, a1, a2, b0, b1, b2);
}

size_t count_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices, size_t stop_after,
                                std::vector<std::pair<uint32_t, uint32_t>>* pairs) {
    if (pairs) pairs->clear();
    const size_t tri_count = indices.size() / 3;
    if (tri_count < 2) return 0;
    Aabb all;
    std::vector<Aabb> boxes(tri_count);
    std::vector<uint8_t> skip(tri_count, 0);
    double extent_sum = 0;
    for (size_t t = 0; t < tri_count; ++t) {
        const Vec3 &a = positions[indices[3 * t]], &b = positions[indices[3 * t + 1]],
                   &c = positions[indices[3 * t + 2]];
        boxes[t].extend(a);
        boxes[t].extend(b);
        boxes[t].extend(c);
        all.extend(boxes[t].min);
        all.extend(boxes[t].max);
        Vec3 s = boxes[t].size();
        extent_sum += std::max({s.x, s.y, s.z});
        if (glm::length(glm::cross(b - a, c - a)) == 0.0) skip[t] = 1;
    }
    const double scale = std::max(all.extent(), 1e-300);
    // Tolerances relative to the model: near-touching within 1e-10 of its size.
    const Predicates pr{1e-15 * scale * scale * scale, 1e-15 * scale * scale};
    Grid grid = make_grid(all, extent_sum / double(tri_count), tri_count);

    // Phase 2: (cell, triangle) entries, sorted by cell.
    std::vector<std::pair<uint64_t, uint32_t>> entries;
    entries.reserve(tri_count * 2);
    for (size_t t = 0; t < tri_count; ++t) {
        if (skip[t]) continue;
        int lo[3], hi[3];
        grid.cell_of(boxes[t].min, lo);
        grid.cell_of(boxes[t].max, hi);
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) entries.push_back({grid.key(x, y, z), uint32_t(t)});
    }
    std::sort(entries.begin(), entries.end());

    // Phase 3: pairs within each cell, tested only in the cell holding the
    // lowest corner of their boxes' overlap.
    size_t found = 0;
    for (size_t begin = 0; begin < entries.size();) {
        size_t end = begin;
        while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
        const uint64_t cell_key = entries[begin].first;
        for (size_t i = begin; i < end; ++i)
            for (size_t j = i + 1; j < end; ++j) {
                uint32_t t1 = entries[i].second, t2 = entries[j].second;
                const Aabb &b1 = boxes[t1], &b2 = boxes[t2];
                Vec3 lo = glm::max(b1.min, b2.min), hi = glm::min(b1.max, b2.max);
                if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) continue;
                int c[3];
                grid.cell_of(lo, c);
                if (grid.key(c[0], c[1], c[2]) != cell_key) continue;
                const uint32_t* A = &indices[3 * size_t(t1)];
                const uint32_t* B = &indices[3 * size_t(t2)];
                int shared = 0, ai[3] = {-1, -1, -1};
                for (int p = 0; p < 3; ++p)
                    for (int q = 0; q < 3; ++q)
                        if (A[p] == B[q]) ai[p] = q;
                for (int p = 0; p < 3; ++p) shared += ai[p] >= 0;
                bool hit = false;
                if (shared == 0) {
                    hit = disjoint_intersect(pr, positions[A[0]], positions[A[1]], positions[A[2]], positions[B[0]],
                                             positions[B[1]], positions[B[2]]);
                } else if (shared == 1) {
                    int p = ai[0] >= 0 ? 0 : (ai[1] >= 0 ? 1 : 2), q = ai[p];
                    hit = vertex_adjacent_intersect(pr, positions[A[p]], positions[A[(p + 1) % 3]],
                                                    positions[A[(p + 2) % 3]], positions[B[(q + 1) % 3]],
                                                    positions[B[(q + 2) % 3]]);
                } else if (shared == 2) {
                    int p = ai[0] < 0 ? 0 : (ai[1] < 0 ? 1 : 2);  // A's vertex not shared
                    int q = 0;
                    while (q < 3 && (B[q] == A[(p + 1) % 3] || B[q] == A[(p + 2) % 3])) ++q;
                    hit = edge_adjacent_intersect(pr, positions[A[(p + 1) % 3]], positions[A[(p + 2) % 3]],
                                                  positions[A[p]], positions[B[q]]);
                } else {
                    hit = true;  // the same triangle twice
                }
                if (!hit) continue;
                if (pairs) pairs->push_back({std::min(t1, t2), std::max(t1, t2)});
                if (++found == stop_after) return found;
            }
        begin = end;
    }
    return found;
}

}  // namespace body
