#pragma once
// Test stacks (cylinder, cone, sphere, branches, holes, ...) and checks on the
// built meshes: closed oriented manifold, positive volume, no degenerate or
// self-intersecting triangles, and re-slicing at every input plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/pipeline/build_pipeline.h"
#include "shared/mesh.h"
#include "shared/mesh_intersect.h"

namespace body::test {

constexpr double kPi = 3.14159265358979323846;

inline std::vector<Vec2> ellipse(double cx, double cy, double a, double b, double theta = 0.0, int n = 32) {
    std::vector<Vec2> pts;
    for (int i = 0; i < n; ++i) {
        const double t = 2 * kPi * i / n, u = a * std::cos(t), v = b * std::sin(t);
        pts.emplace_back(cx + u * std::cos(theta) - v * std::sin(theta),
                         cy + u * std::sin(theta) + v * std::cos(theta));
    }
    return pts;
}
inline std::vector<Vec2> circle(double cx, double cy, double r, int n = 32) { return ellipse(cx, cy, r, r, 0.0, n); }
inline std::vector<Vec2> reversed(std::vector<Vec2> p) {
    std::reverse(p.begin(), p.end());
    return p;
}

struct StackBuilder {
    ContourStack stack;
    StackBuilder& slice(double z, std::vector<std::vector<Vec2>> contours, std::string structure = "") {
        Slice s;
        s.z = z;
        s.source_index = stack.slices.size();
        for (size_t c = 0; c < contours.size(); ++c) {
            Contour contour;
            contour.points = std::move(contours[c]);
            contour.structure = structure;
            contour.source_slice = s.source_index;
            contour.source_contour = c;
            s.contours.push_back(std::move(contour));
        }
        stack.slices.push_back(std::move(s));
        return *this;
    }
};

// --- self-intersections (pairs of triangles meeting away from shared vertices)

inline bool segment_hits_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 d = q - p, e1 = b - a, e2 = c - a, h = glm::cross(d, e2);
    const double det = glm::dot(e1, h);
    const double scale = glm::length(e1) * glm::length(e2) * glm::length(d);
    if (std::abs(det) <= 1e-12 * scale) return false;
    const Vec3 s = p - a;
    const double u = glm::dot(s, h) / det;
    const Vec3 qv = glm::cross(s, e1);
    const double v = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
    const double eps = 1e-9;
    return t > eps && t < 1 - eps && u > eps && v > eps && u + v < 1 - eps;
}

inline size_t count_intersecting_pairs(const Mesh& m) {
    const size_t T = m.triangle_count();
    struct Box {
        Vec3 lo, hi;
        uint32_t t;
    };
    std::vector<Box> boxes(T);
    for (uint32_t t = 0; t < T; ++t) {
        Vec3 lo(1e300), hi(-1e300);
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, m.positions[m.indices[3 * t + k]]);
            hi = glm::max(hi, m.positions[m.indices[3 * t + k]]);
        }
        boxes[t] = {lo, hi, t};
    }
    std::sort(boxes.begin(), boxes.end(), [](const Box& a, const Box& b) { return a.lo.x < b.lo.x; });
    size_t hits = 0;
    for (size_t i = 0; i < T; ++i)
        for (size_t j = i + 1; j < T && boxes[j].lo.x <= boxes[i].hi.x; ++j) {
            const Box &A = boxes[i], &B = boxes[j];
            if (A.lo.y > B.hi.y || B.lo.y > A.hi.y || A.lo.z > B.hi.z || B.lo.z > A.hi.z) continue;
            const uint32_t* a = &m.indices[3 * A.t];
            const uint32_t* b = &m.indices[3 * B.t];
            int shared = 0;
            for (int x = 0; x < 3; ++x)
                for (int y = 0; y < 3; ++y) shared += a[x] == b[y];
            if (shared >= 2) {
                // Folded onto each other: the two opposite vertices coplanar and on the same side.
                uint32_t oa = 0, ob = 0;
                for (int x = 0; x < 3; ++x) {
                    if (a[x] != b[0] && a[x] != b[1] && a[x] != b[2]) oa = a[x];
                    if (b[x] != a[0] && b[x] != a[1] && b[x] != a[2]) ob = b[x];
                }
                const Vec3 &p0 = m.positions[a[0]], &p1 = m.positions[a[1]], &p2 = m.positions[a[2]];
                const Vec3 n = glm::cross(p1 - p0, p2 - p0);
                const double off = glm::dot(m.positions[ob] - p0, n);
                if (std::abs(off) > 1e-12 * glm::length(n) * glm::length(m.positions[ob] - p0)) continue;
                // coplanar: same side of the shared edge?
                uint32_t e0 = 0, e1 = 0;
                int k = 0;
                for (int x = 0; x < 3; ++x)
                    if (a[x] != oa) (k++ == 0 ? e0 : e1) = a[x];
                const Vec3 ed = m.positions[e1] - m.positions[e0];
                const double sa = glm::dot(glm::cross(ed, m.positions[oa] - m.positions[e0]), n);
                const double sb = glm::dot(glm::cross(ed, m.positions[ob] - m.positions[e0]), n);
                if (sa * sb > 0) ++hits;
                continue;
            }
            bool hit = false;
            for (int e = 0; e < 3 && !hit; ++e) {
                const uint32_t p = a[e], q = a[(e + 1) % 3];
                const bool touches =
                    shared == 1 && (p == b[0] || p == b[1] || p == b[2] || q == b[0] || q == b[1] || q == b[2]);
                if (!touches)
                    hit = segment_hits_triangle(m.positions[p], m.positions[q], m.positions[b[0]], m.positions[b[1]],
                                                m.positions[b[2]]);
            }
            for (int e = 0; e < 3 && !hit; ++e) {
                const uint32_t p = b[e], q = b[(e + 1) % 3];
                const bool touches =
                    shared == 1 && (p == a[0] || p == a[1] || p == a[2] || q == a[0] || q == a[1] || q == a[2]);
                if (!touches)
                    hit = segment_hits_triangle(m.positions[p], m.positions[q], m.positions[a[0]], m.positions[a[1]],
                                                m.positions[a[2]]);
            }
            hits += hit;
        }
    return hits;
}

// --- re-slicing

struct Segment2 {
    Vec2 a, b;
};

inline std::vector<Segment2> slice_mesh(const Mesh& m, double z) {
    std::vector<Segment2> out;
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        Vec2 pts[2];
        int k = 0;
        for (int e = 0; e < 3; ++e) {
            const Vec3 p = m.positions[m.indices[t + e]], q = m.positions[m.indices[t + (e + 1) % 3]];
            if ((p.z < z) != (q.z < z)) {
                const double s = (z - p.z) / (q.z - p.z);
                if (k < 2) pts[k] = Vec2(p + (q - p) * s);
                ++k;
            }
        }
        if (k == 2) out.push_back({pts[0], pts[1]});
    }
    return out;
}

inline double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double l2 = glm::dot(ab, ab);
    const double t = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
    return glm::length(a + ab * t - p);
}

inline double distance_to_loop(const Vec2& p, const std::vector<Vec2>& loop) {
    double d = 1e300;
    for (size_t i = 0; i < loop.size(); ++i)
        d = std::min(d, point_segment_distance(p, loop[i], loop[(i + 1) % loop.size()]));
    return d;
}

// Largest deviation between the input contours of slice `s` (those in the mesh's
// structure) and the mesh re-sliced just above or just below that plane; each
// contour is compared on the side where it is reproduced best.
inline double reslice_deviation(const Mesh& m, const std::vector<std::vector<Vec2>>& contours, double z,
                                double extent) {
    const double dz = 1e-7 * extent;
    std::vector<Segment2> sides[2] = {slice_mesh(m, z + dz), slice_mesh(m, z - dz)};
    double worst = 0;
    for (size_t c = 0; c < contours.size(); ++c) {
        double best_side = 1e300;
        for (const auto& segs : sides) {
            double dev = 0;
            for (const Vec2& p : contours[c]) {  // input -> re-slice
                double d = 1e300;
                for (const Segment2& s : segs) d = std::min(d, point_segment_distance(p, s.a, s.b));
                dev = std::max(dev, d);
            }
            for (const Segment2& s : segs) {  // re-slice points nearest this contour -> input
                for (const Vec2& p : {s.a, s.b}) {
                    double mine = distance_to_loop(p, contours[c]), other = 1e300;
                    for (size_t o = 0; o < contours.size(); ++o)
                        if (o != c) other = std::min(other, distance_to_loop(p, contours[o]));
                    if (mine <= other) dev = std::max(dev, mine);
                }
            }
            best_side = std::min(best_side, dev);
        }
        worst = std::max(worst, best_side);
    }
    return worst;
}

// All guarantees for one built structure; `stack` gives the input planes.
inline void expect_good_structure(const StructureMesh& s, const ContourStack& stack, const std::string& structure_id,
                                  bool check_reslice = true) {
    SCOPED_TRACE("structure " + s.id);
    const Aabb box = mesh_bounds(s.mesh.positions);
    const double extent = box.extent();
    const MeshTopology topo = analyze_topology(s.mesh.positions, s.mesh.indices, 1e-14 * extent * extent);
    EXPECT_EQ(topo.boundary_edges, 0u);
    EXPECT_EQ(topo.nonmanifold_edges, 0u);
    EXPECT_EQ(topo.misoriented_edges, 0u);
    EXPECT_EQ(topo.nonmanifold_vertices, 0u);
    EXPECT_EQ(topo.degenerate_triangles, 0u);
    EXPECT_TRUE(topo.closed_manifold());
    EXPECT_GT(s.volume, 0.0);
    EXPECT_EQ(count_intersecting_pairs(s.mesh), 0u);
    EXPECT_EQ(count_self_intersections(s.mesh.positions, s.mesh.indices, 0), 0u);
    if (!check_reslice) return;
    for (const Slice& slice : stack.slices) {
        std::vector<std::vector<Vec2>> contours;
        for (const Contour& c : slice.contours)
            if (structure_id.empty() || c.structure == structure_id) contours.push_back(c.points);
        if (contours.empty()) continue;
        EXPECT_LE(reslice_deviation(s.mesh, contours, slice.z, extent), 1e-4 * extent) << "slice z=" << slice.z;
    }
}

// Largest |distance(p)| over the mesh's surface, 6 x 6 barycentric samples
// per triangle, among the samples `keep(p)` accepts.
template <class Distance, class Keep>
double worst_sampled_distance(const Mesh& mesh, const Distance& distance, const Keep& keep) {
    double worst = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                   c = mesh.positions[mesh.indices[t + 2]];
        for (int i = 0; i <= 6; ++i)
            for (int j = 0; i + j <= 6; ++j) {
                const Vec3 p = a + (b - a) * (i / 6.0) + (c - a) * (j / 6.0);
                if (keep(p)) worst = std::max(worst, std::abs(distance(p)));
            }
    }
    return worst;
}

// The one structure `stack` builds with `rings` interpolated rings per gap (a
// failed build or another count fails the test and gives an empty mesh).
inline StructureMesh build_one(const ContourStack& stack, int rings) {
    BuildOptions options;
    options.interpolate = rings;
    auto built = build_structures(stack, options, "test");
    EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
    if (!built.ok() || built->size() != 1) return {};
    return std::move(built->front());
}

}  // namespace body::test
