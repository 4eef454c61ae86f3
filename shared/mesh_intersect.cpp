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
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "shared/mesh.h"

namespace body {

namespace {

// Exact predicates: coordinates are snapped to a grid of 2^-40 of the model's
// largest dimension and held as integers, so signed volumes (< 2^125) and 2-D
// cross products are exact in 128-bit arithmetic. Points closer than that grid
// step count as touching.
__extension__ typedef __int128 Wide;
using IVec = std::array<int64_t, 3>;
constexpr double kGridSteps = 1099511627776.0;  // 2^40

struct Snap {
    Vec3 origin;
    double scale = 1;  // grid steps per unit
    IVec operator()(const Vec3& p) const {
        IVec q;
        for (int k = 0; k < 3; ++k) q[k] = round_half_away((p[k] - origin[k]) * scale);
        return q;
    }
    static Snap of(const Aabb& box) {
        Snap s;
        s.origin = box.min;
        Vec3 size = box.size();
        double largest = std::max({size.x, size.y, size.z});
        s.scale = largest > 0 ? kGridSteps / largest : 1.0;
        return s;
    }
};

std::array<Wide, 3> sub(const IVec& a, const IVec& b) {
    return {Wide(a[0]) - b[0], Wide(a[1]) - b[1], Wide(a[2]) - b[2]};
}
std::array<Wide, 3> cross(const std::array<Wide, 3>& a, const std::array<Wide, 3>& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
int sign(Wide v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

// Sign of the volume of (a, b, c, d): positive when d is above abc, for the
// points d of one plane abc (its cross product computed once).
// Coordinates lie in [0, 2^40]: differences < 2^41, cross products < 2^82,
// each product n[k] e[k] < 2^123 and their sum < 2^125: no overflow.
// A floating-point filter answers first: the differences are exact in double
// (< 2^41), so Shewchuk's first error bound for orient3d (7.8e-16 of the
// permanent) decides every sign that is not near zero; the rest fall back to
// the exact 128-bit sum.
class Plane {
public:
    Plane(const IVec& a, const IVec& b, const IVec& c) : a_(a), b_(b), c_(c) {
        const double bx = double(b[0] - a[0]), by = double(b[1] - a[1]), bz = double(b[2] - a[2]);
        const double cx = double(c[0] - a[0]), cy = double(c[1] - a[1]), cz = double(c[2] - a[2]);
        n0_ = by * cz - bz * cy, n1_ = bz * cx - bx * cz, n2_ = bx * cy - by * cx;
        p0_ = std::abs(by * cz) + std::abs(bz * cy);
        p1_ = std::abs(bz * cx) + std::abs(bx * cz);
        p2_ = std::abs(bx * cy) + std::abs(by * cx);
    }
    int side(const IVec& d) const {
        const double dx = double(d[0] - a_[0]), dy = double(d[1] - a_[1]), dz = double(d[2] - a_[2]);
        const double det = n0_ * dx + n1_ * dy + n2_ * dz;
        const double bound = 7.7715611723761e-16 * (p0_ * std::abs(dx) + p1_ * std::abs(dy) + p2_ * std::abs(dz));
        if (det > bound) return 1;
        if (det < -bound) return -1;
        auto n = cross(sub(b_, a_), sub(c_, a_));
        auto e = sub(d, a_);
        Wide v = n[0] * e[0] + n[1] * e[1] + n[2] * e[2];
        return sign(v);
    }

private:
    const IVec &a_, &b_, &c_;
    double n0_, n1_, n2_, p0_, p1_, p2_;
};

int orient3(const IVec& a, const IVec& b, const IVec& c, const IVec& d) { return Plane(a, b, c).side(d); }

using IVec2 = std::array<int64_t, 2>;
int orient2(const IVec2& a, const IVec2& b, const IVec2& c) {
    Wide v = (Wide(b[0]) - a[0]) * (Wide(c[1]) - a[1]) - (Wide(b[1]) - a[1]) * (Wide(c[0]) - a[0]);
    return sign(v);
}

// Segment pq against triangle abc (p, q not both in its plane), given the
// sides of abc's plane they lie on (`sp`, `sq`: orient3(a, b, c, p or q)).
bool segment_crosses_triangle(const IVec& p, const IVec& q, int sp, int sq, const IVec& a, const IVec& b,
                              const IVec& c) {
    if (sp == sq) return false;  // same side, or both in the plane (the coplanar case is handled elsewhere)
    int s1 = orient3(p, q, a, b), s2 = orient3(p, q, b, c), s3 = orient3(p, q, c, a);
    bool has_neg = s1 < 0 || s2 < 0 || s3<0, has_pos = s1> 0 || s2 > 0 || s3 > 0;
    return !(has_neg && has_pos);
}

bool segments_cross_2d(const IVec2& a, const IVec2& b, const IVec2& c, const IVec2& d) {
    int o1 = orient2(a, b, c), o2 = orient2(a, b, d), o3 = orient2(c, d, a), o4 = orient2(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    auto on = [](const IVec2& p, const IVec2& q, const IVec2& r) {  // r on segment pq, given collinear
        return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) && std::min(p[1], q[1]) <= r[1] &&
               r[1] <= std::max(p[1], q[1]);
    };
    return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) || (o4 == 0 && on(c, d, b));
}

bool point_in_triangle_2d(const IVec2& p, const IVec2& a, const IVec2& b, const IVec2& c) {
    int s1 = orient2(a, b, p), s2 = orient2(b, c, p), s3 = orient2(c, a, p);
    bool has_neg = s1 < 0 || s2 < 0 || s3<0, has_pos = s1> 0 || s2 > 0 || s3 > 0;
    return !(has_neg && has_pos);
}

// Drops the coordinate along the largest component of abc's normal.
std::array<IVec2, 6> project(const IVec& a, const IVec& b, const IVec& c, std::span<const IVec, 6> v) {
    auto n = cross(sub(b, a), sub(c, a));
    Wide ax = n[0] < 0 ? -n[0] : n[0], ay = n[1] < 0 ? -n[1] : n[1], az = n[2] < 0 ? -n[2] : n[2];
    int drop = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
    std::array<IVec2, 6> out;
    for (int k = 0; k < 6; ++k)
        out[k] = drop == 0 ? IVec2{v[k][1], v[k][2]} : (drop == 1 ? IVec2{v[k][2], v[k][0]} : IVec2{v[k][0], v[k][1]});
    return out;
}

// True when the three signs are all positive or all negative: the points lie
// strictly on one side of the plane.
bool one_side(int s0, int s1, int s2) { return (s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0); }

bool disjoint_intersect(const IVec& a0, const IVec& a1, const IVec& a2, const IVec& b0, const IVec& b1,
                        const IVec& b2) {
    // Möller's early outs: one triangle strictly on one side of the other's plane.
    const Plane pa(a0, a1, a2);
    const int sb0 = pa.side(b0), sb1 = pa.side(b1), sb2 = pa.side(b2);
    if (one_side(sb0, sb1, sb2)) return false;
    const Plane pb(b0, b1, b2);
    const int sa0 = pb.side(a0), sa1 = pb.side(a1), sa2 = pb.side(a2);
    if (one_side(sa0, sa1, sa2)) return false;
    if (sb0 == 0 && sb1 == 0 && sb2 == 0) {
        const IVec v[6] = {a0, a1, a2, b0, b1, b2};
        auto p = project(a0, a1, a2, std::span<const IVec, 6>(v));
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                if (segments_cross_2d(p[i], p[(i + 1) % 3], p[3 + j], p[3 + (j + 1) % 3])) return true;
        return point_in_triangle_2d(p[0], p[3], p[4], p[5]) || point_in_triangle_2d(p[3], p[0], p[1], p[2]);
    }
    return segment_crosses_triangle(a0, a1, sa0, sa1, b0, b1, b2) ||
           segment_crosses_triangle(a1, a2, sa1, sa2, b0, b1, b2) ||
           segment_crosses_triangle(a2, a0, sa2, sa0, b0, b1, b2) ||
           segment_crosses_triangle(b0, b1, sb0, sb1, a0, a1, a2) ||
           segment_crosses_triangle(b1, b2, sb1, sb2, a0, a1, a2) ||
           segment_crosses_triangle(b2, b0, sb2, sb0, a0, a1, a2);
}

// Triangles (v, a, b) and (v, c, d) sharing vertex v: do they meet elsewhere?
bool vertex_adjacent_intersect(const IVec& v, const IVec& a, const IVec& b, const IVec& c, const IVec& d) {
    // Early outs: c and d strictly on one side of (v, a, b)'s plane, or a and b of (v, c, d)'s.
    const Plane pab(v, a, b);
    const int sc = pab.side(c), sd = pab.side(d);
    if (sc * sd > 0) return false;
    const Plane pcd(v, c, d);
    const int sa = pcd.side(a), sb = pcd.side(b);
    if (sa * sb > 0) return false;
    if (sc == 0 && sd == 0) {
        // Both lie in their wedges at v; they overlap iff the wedges do.
        const IVec pts[6] = {v, a, b, v, c, d};
        auto p = project(v, a, b, std::span<const IVec, 6>(pts));
        auto inside = [&](const IVec2& q, const IVec2& o, const IVec2& e1, const IVec2& e2) {  // strictly inside
            int s = orient2(o, e1, e2);
            return s != 0 && orient2(o, e1, q) == s && orient2(o, q, e2) == s;
        };
        auto same_ray = [&](const IVec2& o, const IVec2& e, const IVec2& f) {
            if (orient2(o, e, f) != 0) return false;
            Wide dot = (Wide(e[0]) - o[0]) * (Wide(f[0]) - o[0]) + (Wide(e[1]) - o[1]) * (Wide(f[1]) - o[1]);
            return dot > 0;
        };
        if (inside(p[4], p[0], p[1], p[2]) || inside(p[5], p[0], p[1], p[2]) || inside(p[1], p[0], p[4], p[5]) ||
            inside(p[2], p[0], p[4], p[5]))
            return true;
        return same_ray(p[0], p[1], p[4]) || same_ray(p[0], p[1], p[5]) || same_ray(p[0], p[2], p[4]) ||
               same_ray(p[0], p[2], p[5]);
    }
    // The intersection is a segment from v along the planes' common line; its
    // far end lies on the edge opposite v of one triangle, inside the other.
    return segment_crosses_triangle(a, b, sa, sb, v, c, d) || segment_crosses_triangle(c, d, sc, sd, v, a, b);
}

// Triangles (u, v, a) and (v, u, b) sharing edge uv: they meet beyond it only
// when coplanar with a and b on the same side (folded onto each other).
bool edge_adjacent_intersect(const IVec& u, const IVec& v, const IVec& a, const IVec& b) {
    if (orient3(u, v, a, b) != 0) return false;
    const IVec pts[6] = {u, v, a, u, v, b};
    auto p = project(u, v, a, std::span<const IVec, 6>(pts));
    return orient2(p[0], p[1], p[2]) * orient2(p[0], p[1], p[5]) > 0;
}

struct Grid {
    Vec3 origin;
    double cell = 1;
    int dims[3] = {1, 1, 1};
    void cell_of(const Vec3& p, int out[3]) const {
        for (int k = 0; k < 3; ++k) out[k] = std::clamp(floor_int((p[k] - origin[k]) / cell), 0, dims[k] - 1);
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
    Snap snap = Snap::of(box);
    return disjoint_intersect(snap(a0), snap(a1), snap(a2), snap(b0), snap(b1), snap(b2));
}

namespace {

// Pair test by index adjacency on the snapped positions `q` (the contract's rules).
bool pair_meets(std::span<const IVec> q, const uint32_t* A, const uint32_t* B) {
    static constexpr int kNext[3] = {1, 2, 0}, kPrev[3] = {2, 0, 1};  // (i + 1) % 3, (i + 2) % 3
    int ai[3], shared = 0;                                            // A's corners' places in B, or -1
    for (int p = 0; p < 3; ++p) {
        ai[p] = A[p] == B[0] ? 0 : (A[p] == B[1] ? 1 : (A[p] == B[2] ? 2 : -1));
        shared += ai[p] >= 0;
    }
    if (shared == 0) return disjoint_intersect(q[A[0]], q[A[1]], q[A[2]], q[B[0]], q[B[1]], q[B[2]]);
    if (shared == 1) {
        const int p = ai[0] >= 0 ? 0 : (ai[1] >= 0 ? 1 : 2), k = ai[p];
        return vertex_adjacent_intersect(q[A[p]], q[A[kNext[p]]], q[A[kPrev[p]]], q[B[kNext[k]]], q[B[kPrev[k]]]);
    }
    if (shared == 2) {
        const int p = ai[0] < 0 ? 0 : (ai[1] < 0 ? 1 : 2);  // A's vertex not shared
        const int k = 3 - ai[kNext[p]] - ai[kPrev[p]];      // B's
        return edge_adjacent_intersect(q[A[kNext[p]]], q[A[kPrev[p]]], q[A[p]], q[B[k]]);
    }
    return true;  // the same triangle twice
}

// pair_meets for triangles on either side of one plane z = Z (snapped), A
// below it reaching up to it (its highest corner on it, its lowest below)
// and B above it reaching down to it. They can meet only in that plane, where
// each is the hull of its corners on it: a point or an edge. A vertex they
// share lies there on both, so the shared vertices are the corners on the
// plane that both list, and the contract's rules come down to 2-D: none
// shared, do the two hulls meet; one, do both hulls leave it along one ray
// (edges that would overlap beyond it); two, never (the shared edge, with the
// third corners on opposite sides of it).
bool meet_in_plane(std::span<const IVec> q, const uint32_t* A, const uint32_t* B, int64_t z) {
    uint32_t a[2] = {0, 0}, b[2] = {0, 0};
    int na = 0, nb = 0;
    for (int i = 0; i < 3; ++i) {
        if (q[A[i]][2] == z) a[na++] = A[i];
        if (q[B[i]][2] == z) b[nb++] = B[i];
    }
    if (na == 1) a[1] = a[0];  // a point: a degenerate edge
    if (nb == 1) b[1] = b[0];
    const bool s00 = a[0] == b[0], s01 = a[0] == b[1], s10 = a[1] == b[0], s11 = a[1] == b[1];
    auto xy = [&](uint32_t v) { return IVec2{q[v][0], q[v][1]}; };
    if (!s00 && !s01 && !s10 && !s11) {
        const IVec2 a0 = xy(a[0]), a1 = xy(a[1]), b0 = xy(b[0]), b1 = xy(b[1]);
        for (int k = 0; k < 2; ++k)  // most such pairs are apart along x or y
            if (std::max(a0[k], a1[k]) < std::min(b0[k], b1[k]) || std::max(b0[k], b1[k]) < std::min(a0[k], a1[k]))
                return false;
        return segments_cross_2d(a0, a1, b0, b1);
    }
    // One vertex shared (two shared, or a point's hull, meet only there):
    // both must be edges, collinear, leaving it the same way.
    if (na < 2 || nb < 2 || int(s00) + int(s01) + int(s10) + int(s11) != 1) return false;
    if (s10 || s11) std::swap(a[0], a[1]);  // the shared corner first on both
    if (s01 || s11) std::swap(b[0], b[1]);
    const IVec2 v = xy(a[0]), p = xy(a[1]), r = xy(b[1]);
    if (orient2(v, p, r) != 0) return false;
    const Wide dot = (Wide(p[0]) - v[0]) * (Wide(r[0]) - v[0]) + (Wide(p[1]) - v[1]) * (Wide(r[1]) - v[1]);
    return dot > 0;
}

// A triangle's lowest and highest snapped height.
using Height = std::array<int64_t, 2>;
Height snapped_height(std::span<const IVec> q, const uint32_t* tri) {
    return {std::min({q[tri[0]][2], q[tri[1]][2], q[tri[2]][2]}), std::max({q[tri[0]][2], q[tri[1]][2], q[tri[2]][2]})};
}

// pair_meets, answered in 2-D when the triangles lie on either side of a
// horizontal plane that each reaches (given each one's snapped_height).
bool pair_meets_by_height(std::span<const IVec> q, const uint32_t* A, const uint32_t* B, const Height& a,
                          const Height& b) {
    const auto [a_lo, a_hi] = a;
    const auto [b_lo, b_hi] = b;
    if (a_lo < a_hi && b_lo < b_hi) {
        if (a_hi == b_lo) return meet_in_plane(q, A, B, a_hi);
        if (b_hi == a_lo) return meet_in_plane(q, B, A, b_hi);
    }
    return pair_meets(q, A, B);
}

// One grid cell's candidate pairs, the broad phase shared by the count and
// the layered search. `sweep` holds the cell's entries: each box, `local`
// indexing `low_cell` (the cell of each box's lowest corner), `t` the
// triangle, `marked` whether it is marked. Sorted along x (ties by triangle),
// each entry is paired only with those that start before it ends; a pair is
// passed to `test(i, j)` (entries of `sweep`) when one of its triangles is marked,
// its boxes overlap, and this cell holds the lowest corner of that overlap,
// so each pair is seen in one cell only. Returns true when `test` does (stop).
struct Swept {
    double min_x, max_x, min_y, max_y, min_z, max_z;  // the box, at hand in the sweep's inner loop
    uint32_t t, local;
    bool marked;
    static Swept of(const Aabb& b, uint32_t t, uint32_t local, bool marked) {
        return {b.min.x, b.max.x, b.min.y, b.max.y, b.min.z, b.max.z, t, local, marked};
    }
};
template <class Test>
bool sweep_cell(std::vector<Swept>& sweep, std::span<const std::array<int, 3>> low_cell, const Grid& grid,
                uint64_t cell_key, Test&& test) {
    std::sort(sweep.begin(), sweep.end(),
              [](const Swept& a, const Swept& b) { return a.min_x != b.min_x ? a.min_x < b.min_x : a.t < b.t; });
    for (size_t i = 0; i < sweep.size(); ++i)
        for (size_t j = i + 1; j < sweep.size() && sweep[j].min_x <= sweep[i].max_x; ++j) {
            const Swept &s1 = sweep[i], &s2 = sweep[j];
            if (!s1.marked && !s2.marked) continue;
            if (std::max(s1.min_y, s2.min_y) > std::min(s1.max_y, s2.max_y) ||
                std::max(s1.min_z, s2.min_z) > std::min(s1.max_z, s2.max_z))
                continue;
            // The overlap's lowest corner is the larger of the two lowest corners (cell_of is monotonic).
            const auto &c1 = low_cell[sweep[i].local], &c2 = low_cell[sweep[j].local];
            if (grid.key(std::max(c1[0], c2[0]), std::max(c1[1], c2[1]), std::max(c1[2], c2[2])) != cell_key) continue;
            if (test(i, j)) return true;
        }
    return false;
}

// Phase 1: the snap over the triangles' bounding box, the snapped positions
// and which triangles are degenerate after snapping (skipped).
struct Snapped {
    Aabb all;
    std::vector<Aabb> boxes;
    std::vector<IVec> q;
    std::vector<uint8_t> skip;
    std::vector<Height> height;  // per triangle
    double extent_sum = 0;
};

// A triangle whose snapped corners are collinear has no plane: it is skipped.
// A component of the cross product whose double value is clear of its
// rounding (differences < 2^41 are exact in double, each product is rounded
// once, their difference once) is not zero; the rest are asked exactly.
bool degenerate(const IVec& a, const IVec& b, const IVec& c) {
    const double bx = double(b[0] - a[0]), by = double(b[1] - a[1]), bz = double(b[2] - a[2]);
    const double cx = double(c[0] - a[0]), cy = double(c[1] - a[1]), cz = double(c[2] - a[2]);
    auto clear = [](double p, double q) { return std::abs(p - q) > 1e-15 * (std::abs(p) + std::abs(q)); };
    if (clear(by * cz, bz * cy) || clear(bz * cx, bx * cz) || clear(bx * cy, by * cx)) return false;
    const auto n = cross(sub(b, a), sub(c, a));
    return n[0] == 0 && n[1] == 0 && n[2] == 0;
}

// The distinct vertices of `corners`, ascending: a subset's own numbering
// (local_corner maps a vertex onto it).
std::vector<uint32_t> distinct_corners(std::vector<uint32_t> corners) {
    std::sort(corners.begin(), corners.end());
    corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
    return corners;
}
uint32_t local_corner(const std::vector<uint32_t>& corners, uint32_t v) {
    return uint32_t(std::lower_bound(corners.begin(), corners.end(), v) - corners.begin());
}

Snapped snap_mesh(std::span<const Vec3> positions, std::span<const uint32_t> indices) {
    Snapped m;
    const size_t tri_count = indices.size() / 3;
    m.boxes.resize(tri_count);
    m.skip.assign(tri_count, 0);
    for (size_t t = 0; t < tri_count; ++t) {
        for (int c = 0; c < 3; ++c) m.boxes[t].extend(positions[indices[3 * t + size_t(c)]]);
        m.all.extend(m.boxes[t].min);
        m.all.extend(m.boxes[t].max);
        Vec3 s = m.boxes[t].size();
        m.extent_sum += std::max({s.x, s.y, s.z});
    }
    const Snap snap = Snap::of(m.all);
    m.q.resize(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) m.q[v] = snap(positions[v]);
    m.height.resize(tri_count);
    for (size_t t = 0; t < tri_count; ++t) {
        m.skip[t] = degenerate(m.q[indices[3 * t]], m.q[indices[3 * t + 1]], m.q[indices[3 * t + 2]]);
        m.height[t] = snapped_height(m.q, &indices[3 * t]);
    }
    return m;
}

// Phases 2-3: grid entries sorted by cell, then the pairs within each cell
// (of which one is marked, when `marked` is given), tested only in the cell
// holding the lowest corner of their boxes' overlap.
size_t count_pairs(std::span<const Vec3> positions, std::span<const uint32_t> indices, std::span<const uint8_t> marked,
                   size_t stop_after, std::vector<std::pair<uint32_t, uint32_t>>* pairs) {
    if (pairs) pairs->clear();
    const size_t tri_count = indices.size() / 3;
    if (tri_count < 2) return 0;
    if (indices.size() < positions.size()) {
        // A few triangles of a large mesh: the same count over their corners
        // alone (adjacency by index and the snap box are unchanged by renumbering).
        const std::vector<uint32_t> corners = distinct_corners({indices.begin(), indices.end()});
        std::vector<Vec3> local_positions(corners.size());
        for (size_t i = 0; i < corners.size(); ++i) local_positions[i] = positions[corners[i]];
        std::vector<uint32_t> local(indices.size());
        for (size_t i = 0; i < indices.size(); ++i) local[i] = local_corner(corners, indices[i]);
        return count_pairs(local_positions, local, marked, stop_after, pairs);
    }
    const Snapped m = snap_mesh(positions, indices);
    Grid grid = make_grid(m.all, m.extent_sum / double(tri_count), tri_count);
    std::vector<std::pair<uint64_t, uint32_t>> entries;
    entries.reserve(tri_count * 2);
    std::vector<std::array<int, 3>> low_cell(tri_count);  // the cell of each box's lowest corner
    for (size_t t = 0; t < tri_count; ++t) {
        if (m.skip[t]) continue;
        int* lo = low_cell[t].data();
        int hi[3];
        grid.cell_of(m.boxes[t].min, lo);
        grid.cell_of(m.boxes[t].max, hi);
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) entries.push_back({grid.key(x, y, z), uint32_t(t)});
    }
    std::sort(entries.begin(), entries.end());
    const bool all_marked = marked.empty();
    size_t found = 0;
    std::vector<Swept> sweep;
    for (size_t begin = 0; begin < entries.size();) {
        size_t end = begin;
        bool any_marked = all_marked;
        while (end < entries.size() && entries[end].first == entries[begin].first) {
            any_marked = any_marked || marked[entries[end].second];
            ++end;
        }
        const uint64_t cell_key = entries[begin].first;
        if (!any_marked) {
            begin = end;
            continue;
        }
        sweep.clear();
        for (size_t i = begin; i < end; ++i) {
            const uint32_t t = entries[i].second;
            sweep.push_back(Swept::of(m.boxes[t], t, t, all_marked || marked[t] != 0));
        }
        const bool stopped = sweep_cell(sweep, low_cell, grid, cell_key, [&](size_t i, size_t j) {
            const uint32_t t1 = sweep[i].t, t2 = sweep[j].t;
            if (!pair_meets_by_height(m.q, &indices[3 * size_t(t1)], &indices[3 * size_t(t2)], m.height[t1],
                                      m.height[t2]))
                return false;
            if (pairs) pairs->push_back({std::min(t1, t2), std::max(t1, t2)});
            return ++found == stop_after;
        });
        if (stopped) return found;
        begin = end;
    }
    return found;
}

// One layer's search: `members` are the triangles whose boxes reach into it,
// on a grid of their own (boxes clamped to the layer); a pair is tested in
// the lowest shared cell, and only in the layer holding its overlap's bottom.
// Boxes are the members' own (a layer's arrays stay in cache and are reused).
struct LayerSearch {
    std::span<const Vec3> positions;
    std::span<const uint32_t> indices;
    std::span<const uint8_t> marked;
    std::span<const double> cuts;
    std::span<const IVec> q;
    std::vector<Aabb> boxes;                              // per member
    std::vector<Height> height;                           // per member
    std::vector<std::array<int, 3>> low_cell, high_cell;  // per member
    std::vector<uint32_t> cell_start, fill, in_cell;      // members by cell (CSR)
    std::vector<Swept> sweep;

    void run(size_t layer, std::span<const uint32_t> members, std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
        Aabb bounds;
        double extent_sum = 0;
        boxes.assign(members.size(), Aabb{});
        height.resize(members.size());
        for (size_t i = 0; i < members.size(); ++i) {
            const uint32_t* tri = &indices[3 * size_t(members[i])];
            for (int c = 0; c < 3; ++c) boxes[i].extend(positions[tri[c]]);
            height[i] = snapped_height(q, tri);
            bounds.extend(boxes[i].min);
            bounds.extend(boxes[i].max);
            const Vec3 d = boxes[i].size();
            extent_sum += std::max({d.x, d.y, d.z});
        }
        if (layer > 0) bounds.min.z = std::max(bounds.min.z, cuts[layer - 1]);
        if (layer < cuts.size()) bounds.max.z = std::min(bounds.max.z, cuts[layer]);
        const Grid grid = make_grid(bounds, extent_sum / double(members.size()), members.size());
        // The members by cell (a counting sort: a layer's grid has about as many cells as members).
        const size_t cells = size_t(grid.dims[0]) * size_t(grid.dims[1]) * size_t(grid.dims[2]);
        cell_start.assign(cells + 1, 0);
        low_cell.resize(members.size());
        high_cell.resize(members.size());
        for (uint32_t i = 0; i < members.size(); ++i) {
            int *lo = low_cell[i].data(), *hi = high_cell[i].data();
            grid.cell_of(boxes[i].min, lo);
            grid.cell_of(boxes[i].max, hi);
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) ++cell_start[grid.key(x, y, z) + 1];
        }
        for (size_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
        in_cell.resize(cell_start[cells]);
        fill.assign(cell_start.begin(), cell_start.end() - 1);
        for (uint32_t i = 0; i < members.size(); ++i) {
            const int *lo = low_cell[i].data(), *hi = high_cell[i].data();
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) in_cell[fill[grid.key(x, y, z)]++] = i;
        }
        for (size_t c = 0; c < cells; ++c) {
            bool any_marked = false;
            for (uint32_t k = cell_start[c]; k < cell_start[c + 1] && !any_marked; ++k)
                any_marked = marked[members[in_cell[k]]] != 0;
            if (any_marked && cell_start[c + 1] - cell_start[c] > 1)
                cell(layer, grid, c, cell_start[c], cell_start[c + 1], members, pairs);
        }
    }

    // One cell's pairs, swept along x.
    void cell(size_t layer, const Grid& grid, uint64_t cell_key, size_t begin, size_t end,
              std::span<const uint32_t> members, std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
        sweep.clear();
        for (size_t i = begin; i < end; ++i) {
            const uint32_t local = in_cell[i];
            sweep.push_back(Swept::of(boxes[local], members[local], local, marked[members[local]] != 0));
        }
        sweep_cell(sweep, low_cell, grid, cell_key, [&](size_t i, size_t j) {
            const uint32_t t1 = sweep[i].t, t2 = sweep[j].t;
            // The overlap's bottom lies below this layer's top (both boxes start below it): is it above its floor?
            if (layer > 0 && std::max(sweep[i].min_z, sweep[j].min_z) < cuts[layer - 1]) return false;
            const uint32_t *A = &indices[3 * size_t(t1)], *B = &indices[3 * size_t(t2)];
            if (pair_meets_by_height(q, A, B, height[sweep[i].local], height[sweep[j].local]))
                pairs.push_back({std::min(t1, t2), std::max(t1, t2)});
            return false;
        });
    }
};

// The layers a triangle is listed in, first and last, from its corners'
// layers (`layer`): those its box reaches, less the one above a cut that it
// reaches from below and only touches (its highest corner on the cut).
std::pair<uint32_t, uint32_t> layers_of(std::span<const Vec3> positions, std::span<const uint32_t> layer,
                                        const uint32_t* tri, std::span<const double> cuts) {
    const uint32_t first = std::min({layer[tri[0]], layer[tri[1]], layer[tri[2]]});
    uint32_t last = std::max({layer[tri[0]], layer[tri[1]], layer[tri[2]]});
    if (last > first && cuts[last - 1] == std::max({positions[tri[0]].z, positions[tri[1]].z, positions[tri[2]].z}))
        --last;
    return {first, last};
}

}  // namespace

size_t layer_of(std::span<const double> cuts, double z) {
    return size_t(std::upper_bound(cuts.begin(), cuts.end(), z) - cuts.begin());
}

void self_intersections_by_layer(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                 std::span<const uint8_t> marked, std::span<const double> cuts,
                                 std::vector<std::pair<uint32_t, uint32_t>>& pairs, unsigned threads) {
    pairs.clear();
    const size_t tri_count = indices.size() / 3;
    if (tri_count < 2) return;
    // The snap of the count: over the triangles' corners, every vertex snapped.
    Aabb all;
    for (uint32_t v : indices) all.extend(positions[v]);
    const Snap snap = Snap::of(all);
    std::vector<IVec> q(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) q[v] = snap(positions[v]);
    std::vector<uint32_t> layer(positions.size());
    for (size_t v = 0; v < positions.size(); ++v) layer[v] = uint32_t(layer_of(cuts, positions[v].z));
    // Each triangle that is not degenerate, listed in its layers (CSR by layer).
    std::vector<uint8_t> skip(tri_count), layer_marked(cuts.size() + 1, 0);
    std::vector<uint32_t> start(cuts.size() + 2, 0);
    for (size_t t = 0; t < tri_count; ++t) {
        const uint32_t* tri = &indices[3 * t];
        skip[t] = degenerate(q[tri[0]], q[tri[1]], q[tri[2]]);
        if (skip[t]) continue;
        const auto [first, last] = layers_of(positions, layer, tri, cuts);
        for (size_t l = first; l <= last; ++l) {
            ++start[l + 1];
            layer_marked[l] = layer_marked[l] || marked[t];
        }
    }
    for (size_t l = 0; l + 1 < start.size(); ++l) start[l + 1] += start[l];
    std::vector<uint32_t> members(start.back()), fill(start.begin(), start.end() - 1);
    for (uint32_t t = 0; t < tri_count; ++t) {
        if (skip[t]) continue;
        const auto [first, last] = layers_of(positions, layer, &indices[3 * size_t(t)], cuts);
        for (size_t l = first; l <= last; ++l) members[fill[l]++] = t;
    }
    // The layers to search, the largest first so that threads finish close
    // together; each thread takes the next one and keeps its pairs apart.
    std::vector<uint32_t> todo;
    for (size_t l = 0; l <= cuts.size(); ++l)
        if (layer_marked[l] && start[l + 1] - start[l] > 1) todo.push_back(uint32_t(l));
    std::stable_sort(todo.begin(), todo.end(),
                     [&](uint32_t a, uint32_t b) { return start[a + 1] - start[a] > start[b + 1] - start[b]; });
    const size_t workers = std::clamp<size_t>(threads, 1, std::max<size_t>(todo.size(), 1));
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(workers);
    std::atomic<size_t> next{0};
    auto work = [&](size_t w) {
        LayerSearch search{positions, indices, marked, cuts, q, {}, {}, {}, {}, {}, {}, {}, {}};
        for (size_t k = next++; k < todo.size(); k = next++) {
            const uint32_t l = todo[k];
            search.run(l, std::span<const uint32_t>(members).subspan(start[l], start[l + 1] - start[l]), found[w]);
        }
    };
    if (workers == 1) {
        work(0);
    } else {
        std::vector<std::thread> pool;
        for (size_t w = 1; w < workers; ++w) pool.emplace_back(work, w);
        work(0);
        for (auto& t : pool) t.join();
    }
    for (auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
    std::sort(pairs.begin(), pairs.end());
}

size_t count_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices, size_t stop_after,
                                std::vector<std::pair<uint32_t, uint32_t>>* pairs) {
    return count_pairs(positions, indices, {}, stop_after, pairs);
}

size_t count_self_intersections_of(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                   std::span<const uint8_t> marked, size_t stop_after,
                                   std::vector<std::pair<uint32_t, uint32_t>>* pairs) {
    return count_pairs(positions, indices, marked, stop_after, pairs);
}

std::vector<uint8_t> triangle_pairs_meet(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                         std::span<const std::pair<uint32_t, uint32_t>> pairs) {
    std::vector<uint8_t> out(pairs.size(), 0);
    if (pairs.empty()) return out;
    // The whole mesh's snap (its triangles' bounding box), applied only to the
    // corners of the asked triangles: a few pairs cost one pass over the indices.
    Aabb all;
    for (uint32_t v : indices) all.extend(positions[v]);
    const Snap snap = Snap::of(all);
    std::vector<uint32_t> asked;
    asked.reserve(pairs.size() * 6);
    for (const auto& [t1, t2] : pairs)
        for (uint32_t t : {t1, t2}) asked.insert(asked.end(), &indices[3 * size_t(t)], &indices[3 * size_t(t)] + 3);
    const std::vector<uint32_t> corners = distinct_corners(std::move(asked));
    std::vector<IVec> q(corners.size());
    for (size_t i = 0; i < corners.size(); ++i) q[i] = snap(positions[corners[i]]);
    auto local = [&](uint32_t t, uint32_t tri[3]) {
        for (int c = 0; c < 3; ++c) tri[c] = local_corner(corners, indices[3 * size_t(t) + size_t(c)]);
        return !degenerate(q[tri[0]], q[tri[1]], q[tri[2]]);  // degenerate after snapping: skipped
    };
    for (size_t k = 0; k < pairs.size(); ++k) {
        uint32_t a[3], b[3];
        if (!local(pairs[k].first, a) || !local(pairs[k].second, b)) continue;
        out[k] = pair_meets(q, a, b);
    }
    return out;
}

}  // namespace body
