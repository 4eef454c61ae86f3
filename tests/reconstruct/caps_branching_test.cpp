// Caps (polygon with holes) and the branch partition on their own.
#include <gtest/gtest.h>

#include <map>

#include "builder/branching/branching.h"
#include "builder/branching/hull_ring.h"
#include "builder/branching/union_ring.h"
#include "builder/caps/caps.h"
#include "builder/caps/monotone_cap.h"
#include "builder/contours/validate.h"
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

// The sweep itself (no ear-clipping fallback): every region of the contract
// gives n + 2h - 2 counter-clockwise triangles covering exactly its area.
TEST(MonotoneCap, CoversEachRegionExactly) {
    std::vector<Vec2> comb = {{0, 0}, {10, 0}, {10, 5}, {9, 5}, {9, 1}, {7, 1},
                              {7, 5}, {5, 5},  {5, 1},  {3, 1}, {3, 5}, {0, 5}};
    std::vector<Vec2> stairs;  // a voxel outline: many horizontal and vertical runs, collinear points
    for (int i = 0; i < 20; ++i)
        stairs.insert(stairs.end(), {{double(i), double(i)}, {double(i) + 0.5, double(i)}, {double(i) + 1, double(i)}});
    stairs.insert(stairs.end(), {{20, 20}, {20, 21}, {10, 21}, {0, 21}, {0, 10}});
    std::vector<Vec2> star;  // strongly non-convex
    for (int i = 0; i < 2000; ++i) {
        const double a = 2 * M_PI * i / 2000, r = i % 2 ? 10.0 : 3.0 + (i % 7);
        star.emplace_back(r * std::cos(a), r * std::sin(a));
    }
    auto outer = circle(0, 0, 10, 40), h1 = circle(-4, 0, 2, 12), h2 = reversed(circle(4, 1, 2.5, 14));
    std::vector<std::vector<std::vector<Vec2>>> regions = {{comb}, {stairs}, {star}, {outer, h1, h2}, {reversed(star)}};
    for (size_t c = 0; c < regions.size(); ++c) {
        std::vector<std::span<const Vec2>> loops;
        std::vector<Vec2> all;
        double area = 0;
        for (size_t k = 0; k < regions[c].size(); ++k) {
            const auto& l = regions[c][k];
            loops.emplace_back(l);
            all.insert(all.end(), l.begin(), l.end());
            area += (k == 0 ? 0.5 : -0.5) * std::abs(signed_area2(l.data(), l.size()));
        }
        std::vector<uint32_t> tris;
        ASSERT_TRUE(triangulate_monotone(loops, tris)) << "region " << c;
        EXPECT_EQ(tris.size() / 3, all.size() + 2 * (loops.size() - 1) - 2) << "region " << c;
        double sum = 0;
        for (size_t t = 0; t < tris.size(); t += 3) {
            const Vec2 p = all[tris[t]], q = all[tris[t + 1]], r = all[tris[t + 2]];
            const double s2 = (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
            EXPECT_GE(s2, 0.0) << "region " << c;
            sum += s2 / 2;
        }
        EXPECT_NEAR(sum, area, 1e-9 * area) << "region " << c;
    }
}

TEST(FlatCap, NonConvexComb) {
    std::vector<Vec2> comb = {{0, 0}, {10, 0}, {10, 5}, {9, 5}, {9, 1}, {7, 1},
                              {7, 5}, {5, 5},  {5, 1},  {3, 1}, {3, 5}, {0, 5}};
    std::vector<std::span<const Vec2>> loops{comb};
    std::vector<uint32_t> tris;
    ASSERT_TRUE(triangulate_polygon_with_holes(loops, tris).ok());
    EXPECT_NEAR(triangles_area(comb, tris), signed_area2(comb.data(), comb.size()) / 2, 1e-12);
}

// The pieces glue into one surface with the slab's other side: every contour
// edge in exactly one piece (same direction), every other edge in two pieces,
// traversed in opposite directions; every piece at least a triangle.
void expect_pieces_glue(const std::vector<uint32_t>& ids, const std::vector<std::vector<uint32_t>>& pieces) {
    std::map<std::pair<uint32_t, uint32_t>, int> directed;
    for (const auto& piece : pieces) {
        EXPECT_GE(piece.size(), 3u);
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

std::vector<uint32_t> contour_ids(const std::vector<Vec2>& single, std::vector<Vec3>& positions, double z = 0.0) {
    std::vector<uint32_t> ids;
    for (const Vec2& p : single) {
        ids.push_back(uint32_t(positions.size()));
        positions.emplace_back(p.x, p.y, z);
    }
    return ids;
}

std::vector<Vec2> square(double cx, double cy, double half) {
    return {{cx - half, cy}, {cx, cy - half}, {cx + half, cy}, {cx, cy + half}};
}

TEST(Partition, EveryEdgeOnceChordsTwiceOpposite) {
    auto single = ellipse(0, 0, 14, 6, 0, 40);
    std::vector<Vec3> positions;
    const std::vector<uint32_t> ids = contour_ids(single, positions);
    auto l = circle(-7, 0, 4.5), r = circle(7, 0, 4.5), t = circle(0, 8, 2);
    std::vector<std::span<const Vec2>> branches{l, r, t};
    auto pieces = partition_contour(ids, branches, 0.5, positions);
    ASSERT_TRUE(pieces.ok()) << pieces.error().message;
    ASSERT_EQ(pieces->size(), 3u);
    expect_pieces_glue(ids, *pieces);
}

// A contour with fewer vertices than its branches need (a one-voxel diamond
// over five islands, a triangle over two, a square over eight) still splits:
// branches without an arc bud off a chord, tiny regions are never an error.
TEST(Partition, TooFewVerticesForTheBranchesStillGlue) {
    struct Case {
        std::vector<Vec2> single;
        std::vector<std::vector<Vec2>> branches;
    };
    std::vector<Case> cases;
    cases.push_back(
        {square(0, 0, 0.5),
         {square(0, 0, 0.5), square(1, 0, 0.5), square(-1, 0, 0.5), square(0, 1, 0.5), square(0, -1, 0.5)}});
    cases.push_back({{{0, 0}, {1, 0}, {0, 1}}, {square(0, 0, 0.5), square(1, 1, 0.5)}});
    cases.push_back({{{0, 0}, {1, 0}, {0, 1}}, {square(2, 0, 0.5), square(0, 2, 0.5)}});  // both beside it
    Case ring{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, {}};
    for (int k = 0; k < 8; ++k)
        ring.branches.push_back(square(2 * std::cos(k * kPi / 4), 2 * std::sin(k * kPi / 4), 0.4));
    cases.push_back(ring);
    for (size_t c = 0; c < cases.size(); ++c) {
        SCOPED_TRACE(c);
        for (const bool clockwise : {false, true}) {
            std::vector<Vec3> positions;
            const std::vector<uint32_t> ids =
                contour_ids(clockwise ? reversed(cases[c].single) : cases[c].single, positions);
            std::vector<std::vector<Vec2>> owned;
            for (const auto& b : cases[c].branches) owned.push_back(clockwise ? reversed(b) : b);
            std::vector<std::span<const Vec2>> branches(owned.begin(), owned.end());
            auto pieces = partition_contour(ids, branches, 0.5, positions);
            ASSERT_TRUE(pieces.ok()) << pieces.error().message;
            ASSERT_EQ(pieces->size(), branches.size());
            expect_pieces_glue(ids, *pieces);
            // New vertices lie between the slices; no piece winds against the
            // contour (a chord on the contour's own edge leaves a vertical piece).
            for (size_t v = ids.size(); v < positions.size(); ++v) EXPECT_EQ(positions[v].z, 0.5);
            for (const auto& piece : *pieces) {
                std::vector<Vec2> xy;
                for (uint32_t v : piece) xy.emplace_back(positions[v]);
                EXPECT_GE((clockwise ? -1 : 1) * signed_area2(xy.data(), xy.size()), -1e-12);
            }
        }
    }
}

// A box of voxels as marching squares outlines it after simplification: edges
// on the half-voxel lines, corners cut.
std::vector<Vec2> voxel_box(double x0, double y0, double x1, double y1) {
    return {{x0 + .5, y0}, {x1 - .5, y0}, {x1, y0 + .5}, {x1, y1 - .5},
            {x1 - .5, y1}, {x0 + .5, y1}, {x0, y1 - .5}, {x0, y0 + .5}};
}

// On voxel grids a chord vertex can land exactly between its contour end and a
// branch vertex (AAL Cerebelum_Crus1_R gave one flat triangle that way): the
// vertex next to each chord end must not lie on a segment from that end to a
// branch vertex, or the band can make a zero-area triangle of the three.
// (Each of these boxes had such a vertex before the chords were kept off.)
TEST(Partition, ChordEndsOffTheFanSegmentsOnVoxelGrids) {
    const double boxes[][12] = {
        {1.5, 2.5, 8.5, 10.5, 0.5, 5.5, 1.5, 9.5, -0.5, -0.5, 2.5, 4.5},
        {0.5, 0.5, 8.5, 7.5, 3.5, 3.5, 4.5, 4.5, 5.5, 3.5, 9.5, 4.5},
        {1.5, 0.5, 9.5, 2.5, 3.5, 0.5, 8.5, 2.5, 3.5, 2.5, 7.5, 4.5},
        {2.5, 2.5, 8.5, 9.5, 2.5, 3.5, 7.5, 4.5, 4.5, 5.5, 5.5, 6.5},
        {2.5, 0.5, 4.5, 6.5, 6.5, 3.5, 7.5, 4.5, 1.5, 2.5, 6.5, 7.5},
    };
    for (const auto& box : boxes) {
        SCOPED_TRACE(box[0]);
        const std::vector<Vec2> single = voxel_box(box[0], box[1], box[2], box[3]);
        const std::vector<Vec2> a = voxel_box(box[4], box[5], box[6], box[7]),
                                b = voxel_box(box[8], box[9], box[10], box[11]);
        std::vector<Vec3> positions;
        const std::vector<uint32_t> ids = contour_ids(single, positions, 1.0);
        std::vector<std::span<const Vec2>> branches{a, b};
        auto pieces = partition_contour(ids, branches, 0.5, positions);
        ASSERT_TRUE(pieces.ok()) << pieces.error().message;
        expect_pieces_glue(ids, *pieces);
        size_t chord_ends = 0;
        for (const auto& piece : *pieces)
            for (size_t i = 0; i < piece.size(); ++i) {
                const uint32_t u = piece[i], v = piece[(i + 1) % piece.size()];
                if ((u < ids.size()) == (v < ids.size())) continue;  // not a chord end
                ++chord_ends;
                const Vec2 s(positions[std::min(u, v)]), c(positions[std::max(u, v)]);
                for (const auto& branch : branches)
                    for (const Vec2& p : branch) {
                        const Vec2 d = p - s, e = c - s;
                        const bool between = glm::dot(e, d) > 0 && glm::dot(e, d) < glm::dot(d, d);
                        EXPECT_FALSE(between && std::abs(d.x * e.y - d.y * e.x) < 1e-9)
                            << "chord vertex (" << c.x << ", " << c.y << ") between (" << s.x << ", " << s.y
                            << ") and (" << p.x << ", " << p.y << ")";
                    }
            }
        EXPECT_GE(chord_ends, 4u);
    }
}

TEST(UnionRing, HoldsOverlappingLoopsInsideOneSimpleRing) {
    const auto a = circle(-1.5, 0, 2, 24), b = circle(1.5, 1, 2, 24);
    const std::vector<std::span<const Vec2>> loops{a, b};
    const std::vector<Vec2> ring = union_ring(loops, 0.2);
    ASSERT_GE(ring.size(), 3u);
    EXPECT_GT(signed_area2(ring.data(), ring.size()), 0.0);  // counter-clockwise
    const std::vector<std::span<const Vec2>> alone{ring};
    EXPECT_FALSE(find_crossing(alone).found);
    for (const auto& loop : loops)
        for (const Vec2& p : loop) EXPECT_TRUE(point_in_polygon(p, ring));
}

TEST(UnionRing, EmptyWhenTheUnionIsTwoPieces) {
    const auto a = circle(-10, 0, 2, 24), b = circle(10, 0, 2, 24);
    const std::vector<std::span<const Vec2>> loops{a, b};
    EXPECT_TRUE(union_ring(loops, 0.2).empty());
}

TEST(ConvexHull, CornersOnlyCounterClockwise) {
    const std::vector<Vec2> points{{0, 0}, {2, 0}, {1, 0}, {2, 2}, {1, 1}, {0, 2}, {0, 1}, {2, 2}};
    const std::vector<Vec2> hull = convex_hull(points);
    ASSERT_EQ(hull.size(), 4u);
    EXPECT_GT(signed_area2(hull.data(), hull.size()), 0.0);
    EXPECT_DOUBLE_EQ(signed_area2(hull.data(), hull.size()), 8.0);
}

}  // namespace
}  // namespace body
