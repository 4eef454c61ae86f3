#include "shared/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace body {
namespace {

Mesh cube() {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.positions.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    // Outward-facing, counter-clockwise from outside.
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

TEST(MeshTopology, UnitCubeIsClosedManifoldGenusZero) {
    Mesh m = cube();
    MeshTopology t = analyze_topology(m.positions, m.indices, 1e-12);
    EXPECT_TRUE(t.closed_manifold());
    EXPECT_EQ(t.vertices, 8u);
    EXPECT_EQ(t.edges, 18u);
    EXPECT_EQ(t.components, 1u);
    EXPECT_EQ(t.euler, 2);
    EXPECT_EQ(t.genus(), 0);
    EXPECT_NEAR(mesh_volume(m.positions, m.indices), 1.0, 1e-12);
    EXPECT_NEAR(mesh_area(m.positions, m.indices), 6.0, 1e-12);
}

TEST(MeshTopology, DetectsHoleFlipAndNonManifoldEdge) {
    Mesh open = cube();
    open.indices.resize(open.indices.size() - 3);
    MeshTopology t = analyze_topology(open.positions, open.indices);
    EXPECT_FALSE(t.closed_manifold());
    EXPECT_EQ(t.boundary_edges, 3u);

    Mesh flipped = cube();
    std::swap(flipped.indices[0], flipped.indices[1]);
    t = analyze_topology(flipped.positions, flipped.indices);
    EXPECT_FALSE(t.closed_manifold());
    EXPECT_EQ(t.misoriented_edges, 3u);

    Mesh fin = cube();
    fin.positions.push_back(Vec3(0.5, -1, 0));
    fin.indices.insert(fin.indices.end(), {0, 1, 8});
    t = analyze_topology(fin.positions, fin.indices);
    EXPECT_EQ(t.nonmanifold_edges, 1u);
    EXPECT_FALSE(t.closed_manifold());
}

TEST(MeshTopology, TwoCubesTouchingAtAVertexAreNotVertexManifold) {
    Mesh a = cube(), b = cube();
    // b shares vertex 7 of a at (1,1,1): shift b so its vertex 0 lands there, then weld.
    Mesh m = a;
    uint32_t base = uint32_t(m.positions.size());
    for (const Vec3& p : b.positions) m.positions.push_back(p + Vec3(1, 1, 1));
    for (uint32_t i : b.indices) m.indices.push_back(i == 0 ? 7u : base + i);
    MeshTopology t = analyze_topology(m.positions, m.indices);
    EXPECT_EQ(t.boundary_edges, 0u);
    EXPECT_EQ(t.nonmanifold_vertices, 1u);
    EXPECT_FALSE(t.closed_manifold());
}

TEST(MeshTopology, DegenerateTriangleIsReported) {
    Mesh m = cube();
    m.indices.insert(m.indices.end(), {0, 0, 1});
    EXPECT_EQ(analyze_topology(m.positions, m.indices).degenerate_triangles, 1u);
}

// The link definition, written plainly: a vertex is manifold when the edges
// opposite it (its link) form one path or cycle.
size_t nonmanifold_vertices_by_definition(size_t vertex_count, const std::vector<uint32_t>& indices) {
    size_t bad = 0;
    for (uint32_t v = 0; v < vertex_count; ++v) {
        std::map<uint32_t, std::set<size_t>> edges_at;  // link vertex -> link edges touching it
        std::map<uint32_t, size_t> degree;
        size_t edge = 0;
        for (size_t t = 0; t < indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                if (indices[t + size_t(k)] != v) continue;
                const uint32_t a = indices[t + size_t(k + 1) % 3], b = indices[t + size_t(k + 2) % 3];
                edges_at[a].insert(edge);
                edges_at[b].insert(edge);
                ++degree[a], ++degree[b], ++edge;
            }
        if (edge == 0) continue;
        std::set<uint32_t> reached{edges_at.begin()->first}, todo{edges_at.begin()->first};
        while (!todo.empty()) {  // connectivity through shared link edges
            const uint32_t x = *todo.begin();
            todo.erase(todo.begin());
            for (const auto& [y, at] : edges_at)
                for (size_t e : at)
                    if (edges_at[x].count(e) && reached.insert(y).second) todo.insert(y);
        }
        bool ok = reached.size() == edges_at.size();
        for (const auto& [x, d] : degree) ok = ok && d <= 2;
        bad += !ok;
    }
    return bad;
}

// Random edits of two welded cubes (flips, removals, duplicates, stray
// triangles) give vertices of every kind: fans closed, open, doubled, crossed.
TEST(MeshTopology, NonManifoldVerticesFollowTheLinkDefinition) {
    std::mt19937 rng(7);
    for (int round = 0; round < 200; ++round) {
        Mesh m = cube();
        const uint32_t base = uint32_t(m.positions.size());
        for (const Vec3& p : cube().positions) m.positions.push_back(p + Vec3(1, 1, 1));
        for (uint32_t i : cube().indices) m.indices.push_back(i == 0 ? 7u : base + i);
        std::uniform_int_distribution<size_t> pick_triangle(0, m.indices.size() / 3 - 1);
        std::uniform_int_distribution<uint32_t> pick_vertex(0, uint32_t(m.positions.size() - 1));
        for (int edit = int(rng() % 4); edit > 0; --edit) {
            const size_t t = 3 * pick_triangle(rng);
            switch (rng() % 4) {
                case 0: std::swap(m.indices[t], m.indices[t + 1]); break;
                case 1: m.indices.erase(m.indices.begin() + long(t), m.indices.begin() + long(t) + 3); break;
                case 2: m.indices.insert(m.indices.end(), {m.indices[t], m.indices[t + 1], m.indices[t + 2]}); break;
                default: m.indices.insert(m.indices.end(), {pick_vertex(rng), pick_vertex(rng), pick_vertex(rng)});
            }
        }
        EXPECT_EQ(analyze_topology(m.positions, m.indices).nonmanifold_vertices,
                  nonmanifold_vertices_by_definition(m.positions.size(), m.indices))
            << round;
    }
}

TEST(MeshNormals, CubeCornerNormalPointsOutward) {
    Mesh m = cube();
    auto n = vertex_normals(m.positions, m.indices);
    EXPECT_LT(glm::dot(n[0], Vec3(1, 1, 1)), 0.0);
    EXPECT_GT(glm::dot(n[7], Vec3(1, 1, 1)), 0.0);
    EXPECT_NEAR(glm::length(n[7]), 1.0, 1e-12);
}

}  // namespace
}  // namespace body
