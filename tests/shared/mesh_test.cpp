#include "shared/mesh.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(MeshNormals, CubeCornerNormalPointsOutward) {
    Mesh m = cube();
    auto n = vertex_normals(m.positions, m.indices);
    EXPECT_LT(glm::dot(n[0], Vec3(1, 1, 1)), 0.0);
    EXPECT_GT(glm::dot(n[7], Vec3(1, 1, 1)), 0.0);
    EXPECT_NEAR(glm::length(n[7]), 1.0, 1e-12);
}

}  // namespace
}  // namespace body
