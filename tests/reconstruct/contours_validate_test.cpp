// Validation and repair: every error names slice, contour and reason; repairs warn.
#include <gtest/gtest.h>

#include "builder/contours/validate.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

Status validate_one(std::vector<std::vector<Vec2>> contours, std::vector<std::string>* warnings = nullptr,
                    bool strict = false) {
    StackBuilder b;
    b.slice(0.0, {circle(50, 50, 1)});
    b.slice(1.0, std::move(contours));
    RepairOptions options;
    options.strict = strict;
    RepairLog log;
    auto s = validate_contour_stack(b.stack, "in.json", options, log);
    if (warnings) *warnings = log.lines;
    return s;
}

TEST(Validate, AcceptsSimpleDisjointContours) {
    EXPECT_TRUE(validate_one({circle(0, 0, 5), circle(20, 0, 5), circle(0, 0, 2)}).ok());
}

TEST(Validate, TooFewDistinctPoints) {
    auto s = validate_one({circle(0, 0, 5), {{0, 0}, {1, 1}, {0, 0}, {1, 1}}});
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "in.json: slice 1 contour 1: fewer than 3 distinct points");
    EXPECT_EQ(s.error().exit_code, kExitBadInput);
}

TEST(Validate, ZeroArea) {
    auto s = validate_one({{{0, 0}, {1, 1}, {2, 2}, {3, 3}}});
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "in.json: slice 1 contour 0: zero area");
}

TEST(Validate, NotFinite) {
    auto s = validate_one({{{0, 0}, {1, 0}, {0, std::nan("")}}});
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("slice 1 contour 0: point 2 is not finite"), std::string::npos);
}

TEST(Validate, RemovesDuplicateConsecutivePointsWithAWarning) {
    std::vector<std::string> w;
    auto s = validate_one({{{0, 0}, {0, 0}, {4, 0}, {4, 4}, {0, 4}, {0, 0}}}, &w);
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0],
              "in.json: slice 1 contour 0: at (0, 0): removed 2 duplicate consecutive point(s), points moved up to 0");
}

TEST(Validate, StrictSelfIntersectionNamesThePoint) {
    auto s = validate_one({{{0, 0}, {4, 4}, {4, 0}, {0, 4}}}, nullptr, true);  // a bow tie crossing at (2, 2)
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "in.json: slice 1 contour 0: self-intersects at (2, 2)");
}

TEST(Validate, StrictCrossingContoursNameBothAndThePoint) {
    auto s = validate_one({circle(30, 30, 1), {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, {{2, 1}, {6, 1}, {6, 3}, {2, 3}}},
                          nullptr, true);
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("in.json: slice 1 contour 1: crosses slice 1 contour 2 at (4, "),
              std::string::npos)
        << s.error().message;
}

TEST(Validate, DifferentStructuresMayOverlap) {
    StackBuilder b;
    b.stack.structures = {{"a", "A", {1, 1, 1}}, {"b", "B", {1, 1, 1}}};
    b.slice(0, {circle(0, 0, 5)}, "a");
    b.stack.slices[0].contours.push_back(Contour{circle(3, 0, 5), "b", 0, 1});
    std::vector<std::string> w;
    EXPECT_TRUE(validate_contour_stack(b.stack, "x", w).ok());
}

TEST(Validate, SplitsKeyholes) {
    std::vector<Vec2> key = {{-10, -10}, {10, -10}, {10, 0}, {4, 0},  {4, 4},   {-4, 4},
                             {-4, -4},   {4, -4},   {4, 0},  {10, 0}, {10, 10}, {-10, 10}};
    auto loops = split_keyholes(key);
    ASSERT_EQ(loops.size(), 2u);
    double areas[2] = {std::abs(signed_area2(loops[0].data(), loops[0].size())) / 2,
                       std::abs(signed_area2(loops[1].data(), loops[1].size())) / 2};
    std::sort(areas, areas + 2);
    EXPECT_DOUBLE_EQ(areas[0], 64.0);
    EXPECT_DOUBLE_EQ(areas[1], 400.0);
    std::vector<std::string> w;
    StackBuilder b;
    b.slice(0, {key});
    ASSERT_TRUE(validate_contour_stack(b.stack, "k.json", w).ok());
    EXPECT_EQ(b.stack.slices[0].contours.size(), 2u);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("keyhole"), std::string::npos);
}

TEST(Validate, NestingByEvenOddContainment) {
    auto outer = circle(0, 0, 10), hole = circle(0, 0, 6), island = circle(0, 0, 3), other = circle(30, 0, 2);
    std::vector<std::span<const Vec2>> loops{island, outer, other, hole};
    Nesting n = compute_nesting(loops);
    EXPECT_EQ(n.depth, (std::vector<int>{2, 0, 0, 1}));
    EXPECT_EQ(n.parent, (std::vector<int>{3, -1, -1, 1}));
}

}  // namespace
}  // namespace body
