// Correspondence: overlap areas, ellipse fits, links for 1:1, 1:0, 1:N, N:M, and
// the accuracy comparison that picked the default method.
#include "builder/correspondence/correspondence.h"

#include <gtest/gtest.h>

#include "builder/correspondence/grouping.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

std::vector<Vec2> square(double x0, double y0, double x1, double y1) {
    return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

TEST(Overlap, AreaOfIntersectingSquares) {
    EXPECT_NEAR(polygon_overlap_area(square(0, 0, 4, 4), square(2, 1, 6, 3)), 4.0, 1e-12);
    EXPECT_NEAR(polygon_overlap_area(square(0, 0, 4, 4), reversed(square(2, 1, 6, 3))), 4.0, 1e-12);
    EXPECT_NEAR(polygon_overlap_area(square(0, 0, 4, 4), square(0, 0, 4, 4)), 16.0, 1e-12);  // shared boundary
    EXPECT_NEAR(polygon_overlap_area(square(0, 0, 4, 4), square(1, 1, 2, 2)), 1.0, 1e-12);   // contained
    EXPECT_EQ(polygon_overlap_area(square(0, 0, 1, 1), square(2, 2, 3, 3)), 0.0);
    EXPECT_NEAR(polygon_overlap_area(square(0, 0, 4, 4), square(4, 0, 8, 4)), 0.0, 1e-12);  // touching edge
}

TEST(Overlap, NonConvex) {
    std::vector<Vec2> u = {{0, 0}, {6, 0}, {6, 6}, {4, 6}, {4, 2}, {2, 2}, {2, 6}, {0, 6}};  // a U, area 28
    EXPECT_NEAR(polygon_overlap_area(u, square(1, 1, 5, 5)), 16.0 - 6.0, 1e-12);
}

TEST(Ellipse, FitGivesTheEllipseBack) {
    Ellipse5 e = fit_ellipse(ellipse(3, -2, 8, 3, 0.4, 720));
    EXPECT_NEAR(e.xc, 3, 1e-9);
    EXPECT_NEAR(e.yc, -2, 1e-9);
    EXPECT_NEAR(e.theta, 0.4, 1e-6);
    EXPECT_NEAR(e.a, 8, 1e-3);
    EXPECT_NEAR(e.b, 3, 1e-3);
}

class Methods : public ::testing::TestWithParam<CorrespondenceMethod> {};

TEST_P(Methods, OneToOneAndEnds) {
    auto a = circle(0, 0, 5), b = circle(0.5, 0, 5), far = circle(40, 0, 5);
    std::vector<PolygonSpan> lower{a, far}, upper{b};
    auto links = correspond_contours(lower, upper, GetParam());
    EXPECT_EQ(links, (std::vector<ContourLink>{{0, 0}}));
}

TEST_P(Methods, OneToTwo) {
    auto a = ellipse(0, 0, 14, 6, 0, 40), l = circle(-7, 0, 4.5), r = circle(7, 0, 4.5);
    std::vector<PolygonSpan> lower{a}, upper{l, r};
    EXPECT_EQ(correspond_contours(lower, upper, GetParam()), (std::vector<ContourLink>{{0, 0}, {0, 1}}));
}

INSTANTIATE_TEST_SUITE_P(Both, Methods, ::testing::Values(CorrespondenceMethod::Overlap, CorrespondenceMethod::Ellipse),
                         [](const auto& info) { return std::string(correspondence_method_name(info.param)); });

// The default was chosen on this set of slice pairs with known answers: the
// overlap method gets all of them, the thesis weight misses some.
TEST(CorrespondenceAccuracy, OverlapIsAtLeastAsAccurateAsTheThesisWeight) {
    struct Case {
        std::vector<std::vector<Vec2>> lower, upper;
        std::vector<ContourLink> truth;
    };
    std::vector<Case> cases = {
        {{circle(0, 0, 5)}, {circle(1, 0, 5)}, {{0, 0}}},
        {{circle(0, 0, 5), circle(20, 0, 5)}, {circle(20.5, 0, 5), circle(0.5, 0, 5)}, {{0, 1}, {1, 0}}},
        {{ellipse(0, 0, 14, 6, 0, 40)}, {circle(-7, 0, 4.5), circle(7, 0, 4.5)}, {{0, 0}, {0, 1}}},
        {{circle(0, 0, 12, 48)}, {circle(6, 0, 4), circle(-3, 5.2, 4), circle(-3, -5.2, 4)}, {{0, 0}, {0, 1}, {0, 2}}},
        {{ellipse(-5, 0, 4.5, 3, 0, 28), ellipse(5, 0, 4.5, 3, 0, 28)},
         {ellipse(0, -4, 3.5, 3.5, 0, 28), ellipse(0, 4, 3.5, 3.5, 0, 28)},
         {{0, 0}, {0, 1}, {1, 0}, {1, 1}}},
        {{ellipse(0, 0, 10, 2, 0, 40)}, {ellipse(0, 0, 10, 2, 1.2, 40)}, {{0, 0}}},  // a twisting flat structure
        {{circle(0, 0, 3, 16), circle(9, 0, 3, 16)}, {circle(4.5, 0, 7, 40)}, {{0, 0}, {1, 0}}},  // a merge
        {{circle(0, 0, 5)}, {circle(30, 0, 5)}, {}},  // an end and a start, far apart
    };
    int correct[2] = {0, 0};
    const CorrespondenceMethod methods[2] = {CorrespondenceMethod::Overlap, CorrespondenceMethod::Ellipse};
    for (const Case& c : cases)
        for (int m = 0; m < 2; ++m) {
            std::vector<PolygonSpan> lo(c.lower.begin(), c.lower.end()), up(c.upper.begin(), c.upper.end());
            const bool ok = correspond_contours(lo, up, methods[m]) == c.truth;
            if (!ok)
                std::printf("case %zu: %s misses\n", size_t(&c - cases.data()), correspondence_method_name(methods[m]));
            correct[m] += ok;
        }
    std::printf("correspondence accuracy on %zu cases: overlap %d, ellipse %d\n", cases.size(), correct[0], correct[1]);
    EXPECT_EQ(correct[0], int(cases.size()));
    EXPECT_GE(correct[0], correct[1]);
}

TEST(Grouping, LinkGroupsAreConnectedComponents) {
    const std::vector<ContourLink> links{{0, 0}, {1, 0}, {2, 1}, {2, 2}};
    const auto groups = group_links(links, 3, 3);
    ASSERT_EQ(groups.size(), 2u);
    const auto& merge = groups[0].lower.size() == 2 ? groups[0] : groups[1];
    const auto& split = groups[0].lower.size() == 2 ? groups[1] : groups[0];
    EXPECT_EQ(merge.lower, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(merge.upper, (std::vector<uint32_t>{0}));
    EXPECT_EQ(merge.links, (std::vector<ContourLink>{{0, 0}, {1, 0}}));
    EXPECT_EQ(split.lower, (std::vector<uint32_t>{2}));
    EXPECT_EQ(split.upper, (std::vector<uint32_t>{1, 2}));
}

TEST(Grouping, UnlabelledContoursFollowCorrespondenceAndHolesTheirParent) {
    ContourStack stack;
    stack.structures.push_back({"kidney", "Kidney", Vec3(0.5)});
    stack.slices.resize(2);
    stack.slices[0].z = 0;
    stack.slices[1].z = 1;
    auto add = [&](size_t s, std::vector<Vec2> points, std::string structure = "") {
        stack.slices[s].contours.push_back(Contour{std::move(points), std::move(structure), s, 0});
    };
    add(0, circle(0, 0, 5));             // auto_1
    add(0, circle(0, 0, 2));             // its hole
    add(0, circle(20, 0, 3));            // auto_2 (no partner above)
    add(0, circle(40, 0, 3), "kidney");  // labelled
    add(1, circle(0.5, 0, 4));           // auto_1 continues
    const StructureGroups g = group_structures(stack, CorrespondenceMethod::Overlap);
    ASSERT_EQ(g.infos.size(), 3u);
    EXPECT_EQ(g.infos[0].id, "kidney");
    EXPECT_EQ(g.infos[1].id, "auto_1");
    EXPECT_EQ(g.infos[1].name, "structure 1");
    EXPECT_EQ(g.infos[2].id, "auto_2");
    EXPECT_EQ(g.members[0][0], (std::vector<uint32_t>{3}));
    EXPECT_EQ(g.members[1][0], (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(g.members[1][1], (std::vector<uint32_t>{0}));
    EXPECT_EQ(g.members[2][0], (std::vector<uint32_t>{2}));
    EXPECT_TRUE(g.members[2][1].empty());
}

}  // namespace
}  // namespace body
