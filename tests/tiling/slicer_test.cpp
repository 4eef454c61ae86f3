// slice_mesh: closed meshes give closed counter-clockwise contours on the
// surface; holes come out clockwise; planes through vertices still close;
// open meshes are errors naming the plane.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "builder/slicing/mesh_slicer.h"
#include "shared/mesh.h"
#include "tests/common/test_meshes.h"

namespace {

using body::Vec2;
using body::Vec3;

body::Mesh box_mesh(Vec3 lo, Vec3 hi) {
    body::Mesh m;
    for (int k = 0; k < 8; ++k) m.positions.push_back({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
    // Outward-facing quads (counter-clockwise seen from outside), split in two.
    const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& f : q) m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    return m;
}

body::Mesh torus(int rings, int segments, double big, double small) {
    body::Mesh m;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            double u = 2 * M_PI * i / rings, v = 2 * M_PI * j / segments;
            m.positions.push_back({(big + small * std::cos(v)) * std::cos(u), (big + small * std::cos(v)) * std::sin(u),
                                   small * std::sin(v)});
        }
    auto id = [&](int i, int j) { return uint32_t((i % rings) * segments + (j % segments)); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j)
            m.indices.insert(m.indices.end(),
                             {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    return m;
}

double area(const std::vector<Vec2>& c) { return 0.5 * body::signed_area2(c.data(), c.size()); }

TEST(Slicer, CubeGivesOneSquarePerPlane) {
    auto m = box_mesh({-1, -2, -3}, {1, 2, 3});
    ASSERT_GT(body::mesh_volume(m.positions, m.indices), 0.0);
    auto planes = body::evenly_spaced_planes(-3, 3, 6);
    auto stack = body::slice_mesh(m.positions, m.indices, 2, planes, "cube");
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), 6u);
    for (size_t s = 0; s < 6; ++s) {
        EXPECT_NEAR(stack->slices[s].z, planes[s], 1e-12);
        ASSERT_EQ(stack->slices[s].contours.size(), 1u);
        const auto& c = stack->slices[s].contours[0];
        EXPECT_EQ(c.structure, "cube");
        EXPECT_NEAR(area(c.points), 8.0, 1e-9);  // counter-clockwise: positive
        for (const Vec2& p : c.points) EXPECT_NEAR(std::max(std::abs(p.x), std::abs(p.y) / 2), 1.0, 1e-9);
    }
    // Along x: contours in (y, z), of area 4 * 6.
    auto side = body::slice_mesh(m.positions, m.indices, 0, body::evenly_spaced_planes(-1, 1, 3));
    ASSERT_TRUE(side.ok());
    ASSERT_EQ(side->slices.size(), 3u);
    EXPECT_NEAR(area(side->slices[1].contours[0].points), 24.0, 1e-9);
}

TEST(Slicer, SpherePlanesThroughVerticesStillClose) {
    const int rings = 16;
    auto m = body::test::uv_sphere(rings, 32);
    std::vector<double> planes;
    for (int r = 1; r < rings; ++r) planes.push_back(std::cos(M_PI * r / rings));  // exactly the vertex rings
    planes.push_back(1.0);                                                         // touching the pole only
    planes.push_back(0.123);
    auto stack = body::slice_mesh(m.positions, m.indices, 2, planes);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), size_t(rings));  // the pole plane gives no contour
    for (const auto& slice : stack->slices) {
        ASSERT_EQ(slice.contours.size(), 1u) << slice.z;
        const auto& c = slice.contours[0];
        double r = std::sqrt(std::max(0.0, 1 - slice.z * slice.z));
        EXPECT_GT(area(c.points), 0.0);
        EXPECT_LE(area(c.points), M_PI * r * r);
        EXPECT_GT(area(c.points), 0.9 * M_PI * r * r);
        for (const Vec2& p : c.points) EXPECT_LE(glm::length(p), r + 1e-9);
        EXPECT_GE(c.points.size(), 32u);
    }
}

TEST(Slicer, TorusGivesOuterWallAndClockwiseHole) {
    auto m = torus(48, 24, 3, 1);
    ASSERT_GT(body::mesh_volume(m.positions, m.indices), 0.0);
    auto stack = body::slice_mesh(m.positions, m.indices, 2, std::vector<double>{0.0, 0.5});
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), 2u);
    for (const auto& slice : stack->slices) {
        ASSERT_EQ(slice.contours.size(), 2u);
        double a0 = area(slice.contours[0].points), a1 = area(slice.contours[1].points);
        EXPECT_LT(std::min(a0, a1), 0.0);  // the hole
        EXPECT_GT(std::max(a0, a1), 0.0);  // the outer wall
        EXPECT_GT(std::max(a0, a1), -std::min(a0, a1));
    }
    // Along x through the tube: two separate discs, both counter-clockwise.
    auto across = body::slice_mesh(m.positions, m.indices, 0, std::vector<double>{0.01});
    ASSERT_TRUE(across.ok());
    ASSERT_EQ(across->slices[0].contours.size(), 2u);
    EXPECT_GT(area(across->slices[0].contours[0].points), 0.0);
    EXPECT_GT(area(across->slices[0].contours[1].points), 0.0);
}

TEST(Slicer, OpenMeshAndBadIndicesAreErrors) {
    auto m = box_mesh({0, 0, 0}, {1, 1, 1});
    m.indices.resize(m.indices.size() - 6);  // remove the last face
    auto stack = body::slice_mesh(m.positions, m.indices, 2, std::vector<double>{0.25, 0.5});
    ASSERT_FALSE(stack.ok());
    EXPECT_NE(stack.error().message.find("plane 0"), std::string::npos) << stack.error().message;
    EXPECT_NE(stack.error().message.find("open"), std::string::npos);
    m = box_mesh({0, 0, 0}, {1, 1, 1});
    m.indices[5] = 99;
    stack = body::slice_mesh(m.positions, m.indices, 2, std::vector<double>{0.5});
    ASSERT_FALSE(stack.ok());
    EXPECT_NE(stack.error().message.find("index 5"), std::string::npos);
}

// A unit sphere with a small box poking through its side over z in [-0.02,
// 0.02]: the plane at z = 0 crosses the self-intersection (the sphere's
// triangles there span |z| < 0.066). It moves just past the
// span (no double gap), the others stay, and every slice holds one contour
// (the overlap's contours would cross).
TEST(Slicer, PlanesMoveOffSelfIntersectionsInsteadOfLeavingAGap) {
    auto m = body::test::uv_sphere(48, 48);
    const auto poke = box_mesh({0.9, -0.1, -0.02}, {1.2, 0.1, 0.02});
    const uint32_t base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), poke.positions.begin(), poke.positions.end());
    for (uint32_t i : poke.indices) m.indices.push_back(base + i);
    const auto given = body::evenly_spaced_planes(-1, 1, 9);  // the fifth is at z = 0
    auto dropped = given;
    EXPECT_EQ(body::drop_planes_through_self_intersections(m.positions, m.indices, 2, dropped), 1u);
    auto planes = given;
    const body::PlaneMoves moves = body::move_planes_off_self_intersections(m.positions, m.indices, 2, planes);
    EXPECT_EQ(moves.moved, 1u);
    EXPECT_EQ(moves.dropped, 0u);
    ASSERT_EQ(planes.size(), given.size());
    const double gap = given[1] - given[0];
    for (size_t k = 0; k < planes.size(); ++k) {
        if (k == 4) {
            EXPECT_GT(std::abs(planes[k]), 0.02) << planes[k];
            EXPECT_LE(std::abs(planes[k] - given[k]), body::kPlaneMoveLimit * gap);
        } else {
            EXPECT_EQ(planes[k], given[k]);
        }
        if (k > 0) {
            EXPECT_GE(planes[k] - planes[k - 1], (1 - 2 * body::kPlaneMoveLimit) * gap);
        }
    }
    auto stack = body::slice_mesh(m.positions, m.indices, 2, planes);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), given.size());
    for (const auto& slice : stack->slices) EXPECT_EQ(slice.contours.size(), 1u);
    // A plane with no room to move (the span covers its whole neighbourhood) is left out.
    auto wide = box_mesh({0.9, -0.1, -0.8}, {1.2, 0.1, 0.8});
    body::Mesh w = body::test::uv_sphere(48, 48);
    const uint32_t wb = uint32_t(w.positions.size());
    w.positions.insert(w.positions.end(), wide.positions.begin(), wide.positions.end());
    for (uint32_t i : wide.indices) w.indices.push_back(wb + i);
    planes = given;
    const body::PlaneMoves none = body::move_planes_off_self_intersections(w.positions, w.indices, 2, planes);
    EXPECT_EQ(none.dropped, 7u);  // |z| < 0.8: the middle seven
    EXPECT_EQ(none.moved, 0u);
    EXPECT_EQ(planes.size(), 2u);
}

}  // namespace
