// Caps (polygon with holes) and the branch partition on their own.
#include <gtest/gtest.h>

#include <map>

#include "builder/branching/branching.h"
#include "builder/caps/caps.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

double triangles_area(const std::vector<Vec2>& pts, const std::vector<uint32_t>& tris) {
    double a = 0;
    for (size_t t = 0; t < tris.size(); t += 3) {
        const Vec2 p = pts[tris[t]], q = pts[tris[t + 1]], r = pts[tris[t + 2]];
        const double s = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
        EXPECT_GT(s, 0.0);  // counter-clockwise, not degenerate
        a += s / 2;
    }
    return a;
}

TEST(FlatCap, PolygonWithTwoHoles) {
    auto outer = circle(0, 0, 10, 40), h1 = circle(-4, 0, 2, 12), h2 = reversed(circle(4, 1, 2.5, 14));
    std::vector<std::span<const Vec2>> loops{outer, h1, h2};
    std::vector<uint32_t> tris;
    ASSERT_TRUE(triangulate_polygon_with_holes(loops, tris).ok());
    std::vector<Vec2> all(outer);
    all.insert(all.end(), h1.begin(), h1.end());
    all.insert(all.end(), h2.begin(), h2.end());
    const double expect =
        (std::abs(signed_area2(outer.data(), outer.size())) - std::abs(signed_area2(h1.data(), h1.size())) -
         std::abs(signed_area2(h2.data(), h2.size()))) /
        2;
    EXPECT_NEAR(triangles_area(all, tris), expect, 1e-9 * expect);
    EXPECT_EQ(tris.size() / 3, all.size() + 2 * 2 - 2);  // n + 2h - 2 triangles
}

TEST(FlatCap, NonConvexComb) {
    std::vector<Vec2> comb = {{0, 0}, {10, 0}, {10, 5}, {9, 5}, {9, 1}, {7, 1},
                              {7, 5}, {5, 5},  {5, 1},  {3, 1}, {3, 5}, {0, 5}};
    std::vector<std::span<const Vec2>> loops{comb};
    std::vector<uint32_t> tris;
    ASSERT_TRUE(triangulate_polygon_with_holes(loops, tris).ok());
    EXPECT_NEAR(triangles_area(comb, tris), signed_area2(comb.data(), comb.size()) / 2, 1e-12);
}

TEST(Partition, EveryEdgeOnceChordsTwiceOpposite) {
    auto single = ellipse(0, 0, 14, 6, 0, 40);
    std::vector<Vec3> positions;
    std::vector<uint32_t> ids;
    for (const Vec2& p : single) {
        ids.push_back(uint32_t(positions.size()));
        positions.emplace_back(p.x, p.y, 0.0);
    }
    auto l = circle(-7, 0, 4.5), r = circle(7, 0, 4.5), t = circle(0, 8, 2);
    std::vector<std::span<const Vec2>> branches{l, r, t};
    auto pieces = partition_contour(ids, branches, 0.5, positions);
    ASSERT_TRUE(pieces.ok()) << pieces.error().message;
    ASSERT_EQ(pieces->size(), 3u);
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const auto& piece : *pieces) {
        ASSERT_GE(piece.size(), 3u);
        for (size_t i = 0; i < piece.size(); ++i) directed[{piece[i], piece[(i + 1) % piece.size()]}]++;
    }
    for (size_t i = 0; i < ids.size(); ++i) EXPECT_EQ((directed[{ids[i], ids[(i + 1) % ids.size()]}]), 1);
    for (const auto& [edge, count] : directed) {
        EXPECT_EQ(count, 1);
        const bool contour_edge = edge.first < ids.size() && edge.second < ids.size();
        if (!contour_edge) {
            EXPECT_EQ((directed.count({edge.second, edge.first})), 1u);
        }
    }
}

}  // namespace
}  // namespace body
