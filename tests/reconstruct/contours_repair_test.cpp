// Contour repair: each problem with its reference outcome (what remains, which
// repair was counted, how far points moved), refusals beyond the tolerance,
// strict mode, and the crossing finder on many nested rings.
#include <gtest/gtest.h>

#include "builder/contours/repair.h"
#include "builder/contours/validate.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

double area_of(const std::vector<Vec2>& p) { return std::abs(signed_area2(p.data(), p.size())) / 2; }

double total_area(const Slice& s) {
    double a = 0;
    for (const Contour& c : s.contours) a += area_of(c.points);
    return a;
}

bool no_crossings(const Slice& s) {
    std::vector<std::span<const Vec2>> loops;
    for (const Contour& c : s.contours) loops.emplace_back(c.points);
    return find_crossings(loops).empty();
}

struct Repaired {
    Status status = ok_status();
    ContourStack stack;
    RepairLog log;
};

// Slice 0: a far circle; slice 1: `contours`. Tolerance 0.1 unless given.
Repaired repair(std::vector<std::vector<Vec2>> contours, double tolerance = 0.1, bool strict = false) {
    StackBuilder b;
    b.slice(0.0, {circle(50, 50, 1)});
    b.slice(1.0, std::move(contours));
    Repaired r;
    RepairOptions o;
    o.tolerance = tolerance;
    o.strict = strict;
    r.status = validate_contour_stack(b.stack, "in.json", o, r.log);
    r.stack = std::move(b.stack);
    return r;
}

const std::vector<Vec2> kSquare = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};

TEST(Repair, FigureEightSplitsIntoItsLobesApart) {
    Repaired r = repair({{{0, 0}, {4, 4}, {4, 0}, {0, 4}}});
    ASSERT_TRUE(r.status.ok()) << r.status.error().message;
    const Slice& s = r.stack.slices[1];
    ASSERT_EQ(s.contours.size(), 2u);
    EXPECT_NEAR(area_of(s.contours[0].points), 4.0, 5e-3);  // the shared point pulled in by 1e-2 x tolerance
    EXPECT_NEAR(area_of(s.contours[1].points), 4.0, 5e-3);
    EXPECT_NEAR(total_area(s), 8.0, 1e-2);
    EXPECT_TRUE(no_crossings(s));
    EXPECT_EQ(r.log.counts["self_intersection"], 1u);
    EXPECT_EQ(r.log.counts["touching"], 1u);
    EXPECT_NE(r.log.lines[0].find("in.json: slice 1 contour 0: at (2, 2): self-intersection repaired into 2"),
              std::string::npos)
        << r.log.lines[0];
}

TEST(Repair, ZigZagTwistDropsItsSliverWithinTheTolerance) {
    // A circle whose edge 10 -> 11 is replaced by a small twisted loop 0.03 across.
    auto c = circle(0, 0, 10, 64);
    const double before = area_of(c);
    std::vector<Vec2> zig(c.begin(), c.begin() + 10);
    zig.push_back(c[10] + Vec2(0.02, 0.0));
    zig.push_back(c[9] + Vec2(0.0, 0.03));
    zig.insert(zig.end(), c.begin() + 10, c.end());
    Repaired r = repair({zig});
    ASSERT_TRUE(r.status.ok()) << r.status.error().message;
    const Slice& s = r.stack.slices[1];
    ASSERT_EQ(s.contours.size(), 1u);
    EXPECT_NEAR(area_of(s.contours[0].points), before, 0.01);
    EXPECT_TRUE(no_crossings(s));
    EXPECT_EQ(r.log.counts["self_intersection"], 1u);
    EXPECT_NE(r.log.lines[0].find("1 sliver(s) dropped"), std::string::npos) << r.log.lines[0];
    // Every point left is an input point, bit for bit, or a crossing point near the twist.
    size_t kept = 0;
    for (const Vec2& p : s.contours[0].points) kept += std::find(zig.begin(), zig.end(), p) != zig.end();
    EXPECT_GE(kept, c.size() - 2);
    // With a tolerance smaller than the twist the sliver stays a contour of its own.
    Repaired tight = repair({zig}, 1e-4);
    ASSERT_TRUE(tight.status.ok()) << tight.status.error().message;
    EXPECT_EQ(tight.stack.slices[1].contours.size(), 2u);
}

TEST(Repair, OverlappingContoursOfOneStructureAreUnioned) {
    Repaired r = repair({kSquare, {{5, 5}, {15, 5}, {15, 15}, {5, 15}}});
    ASSERT_TRUE(r.status.ok()) << r.status.error().message;
    const Slice& s = r.stack.slices[1];
    ASSERT_EQ(s.contours.size(), 1u);
    EXPECT_DOUBLE_EQ(area_of(s.contours[0].points), 175.0);
    EXPECT_EQ(r.log.counts["overlap"], 1u);
    EXPECT_NE(r.log.lines[0].find("union of 2 overlapping contours (0, 1)"), std::string::npos) << r.log.lines[0];
}

TEST(Repair, HoleInsideItsStructureIsKept) {
    Repaired r = repair({kSquare, {{2, 2}, {8, 2}, {8, 8}, {2, 8}}});
    ASSERT_TRUE(r.status.ok());
    EXPECT_EQ(r.stack.slices[1].contours.size(), 2u);
    EXPECT_TRUE(r.log.lines.empty());
}

TEST(Repair, DifferentStructuresOverlappingAreWarnedAndKept) {
    StackBuilder b;
    b.stack.structures = {{"a", "A", {1, 1, 1}}, {"b", "B", {1, 1, 1}}};
    b.slice(0, {kSquare}, "a");
    b.stack.slices[0].contours.push_back(Contour{{{5, 5}, {15, 5}, {15, 15}, {5, 15}}, "b", 0, 1});
    RepairLog log;
    ASSERT_TRUE(validate_contour_stack(b.stack, "x", RepairOptions{}, log).ok());
    EXPECT_EQ(b.stack.slices[0].contours.size(), 2u);
    EXPECT_EQ(b.stack.slices[0].contours[0].points, kSquare);
    EXPECT_EQ(log.counts["structure_overlap"], 1u);
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_NE(
        log.lines[0].find("structure 'a' crosses slice 0 contour 1 of structure 'b' (both kept; the two cross on 1 "
                          "slice(s))"),
        std::string::npos)
        << log.lines[0];
}

TEST(Repair, NearDuplicateCollinearAndSpikePointsGo) {
    // (5, 0) on a straight edge, (10, 1e-6) next to (10, 0), a spike folding back along the top edge to (5, 10).
    std::vector<Vec2> p = {{0, 0}, {5, 0}, {10, 0}, {10, 1e-6}, {10, 10}, {5, 10}, {5.05, 10}, {0, 10}};
    Repaired r = repair({p});
    ASSERT_TRUE(r.status.ok()) << r.status.error().message;
    const auto& q = r.stack.slices[1].contours[0].points;
    EXPECT_EQ(q.size(), 4u);
    EXPECT_DOUBLE_EQ(area_of(q), 100.0);
    EXPECT_EQ(r.log.counts["near_duplicate"], 1u);
    EXPECT_EQ(r.log.counts["collinear"], 1u);
    EXPECT_EQ(r.log.counts["spike"], 1u);
    bool spike_line = false;
    for (const auto& l : r.log.lines)
        spike_line |=
            l.find("at (5, 10): removed 1 zero-width spike tip(s), points moved up to 0.05") != std::string::npos;
    EXPECT_TRUE(spike_line);
}

TEST(Repair, LongSpikeIsRefusedWithThePlace) {
    std::vector<Vec2> p = {{0, 0}, {10, 0}, {10, 10}, {5, 10}, {5, 30}, {5, 10}, {0, 10}};
    Repaired r = repair({p});
    ASSERT_FALSE(r.status.ok());
    EXPECT_EQ(r.status.error().message,
              "in.json: slice 1 contour 0: zero-width spike at (5, 30); repairing it would move points by 20 (more "
              "than the repair tolerance 0.1)");
    EXPECT_EQ(r.status.error().exit_code, kExitBadInput);
}

TEST(Repair, TinyDegenerateContourIsDroppedLargeOneRefused) {
    Repaired r = repair({kSquare, {{20, 20}, {20.01, 20.01}, {20.02, 20.02}}});
    ASSERT_TRUE(r.status.ok()) << r.status.error().message;
    EXPECT_EQ(r.stack.slices[1].contours.size(), 1u);
    EXPECT_EQ(r.log.counts["degenerate"], 1u);
    Repaired big = repair({kSquare, {{20, 20}, {21, 21}, {22, 22}}});
    ASSERT_FALSE(big.status.ok());
    EXPECT_EQ(big.status.error().message, "in.json: slice 1 contour 1: zero area");
}

TEST(Repair, StrictRefusesWhatRepairFixes) {
    Repaired r = repair({kSquare, {{5, 5}, {15, 5}, {15, 15}, {5, 15}}}, 0.1, true);
    ASSERT_FALSE(r.status.ok());
    EXPECT_EQ(r.status.error().message, "in.json: slice 1 contour 0: crosses slice 1 contour 1 at (5, 10)");
    Repaired spike = repair({{{0, 0}, {10, 0}, {10, 10}, {5, 10}, {5.05, 10}, {0, 10}}}, 0.1, true);
    ASSERT_FALSE(spike.status.ok());
    EXPECT_NE(spike.status.error().message.find("self-intersects at (5, 10"), std::string::npos)
        << spike.status.error().message;
}

TEST(Repair, RepairedStackValidatesWithoutFurtherRepairs) {
    StackBuilder b;
    b.slice(0.0, {{{0, 0}, {4, 4}, {4, 0}, {0, 4}}});
    b.slice(1.0, {kSquare, {{5, 5}, {15, 5}, {15, 15}, {5, 15}}});
    RepairLog first, second;
    ASSERT_TRUE(validate_contour_stack(b.stack, "x", RepairOptions{}, first).ok());
    EXPECT_FALSE(first.lines.empty());
    ASSERT_TRUE(validate_contour_stack(b.stack, "x", RepairOptions{}, second).ok());
    EXPECT_TRUE(second.lines.empty()) << second.lines[0];
}

TEST(Repair, DefaultToleranceFollowsTheStackExtent) {
    StackBuilder b;
    b.slice(0.0, {{{0, 0}, {300, 0}, {300, 400}, {0, 400}}});
    EXPECT_DOUBLE_EQ(repair_tolerance(b.stack, RepairOptions{}), 500 * kDefaultRepairTolerance);
    RepairOptions o;
    o.tolerance = 0.25;
    EXPECT_DOUBLE_EQ(repair_tolerance(b.stack, o), 0.25);
}

TEST(Crossings, FindsEveryMeetingPairAmongManyNestedRings) {
    // 150 concentric rings 0.5 apart (the case the x-sweep took quadratic time
    // on), ring 40 shifted across rings 39 and 41, and a ring twisted into a bow tie.
    std::vector<std::vector<Vec2>> rings;
    for (int k = 0; k < 150; ++k) rings.push_back(circle(k == 40 ? 0.7 : 0.0, 0, 10 + 0.5 * k, 96));
    rings.push_back({{100, 100}, {104, 104}, {104, 100}, {100, 104}});
    std::vector<std::span<const Vec2>> loops(rings.begin(), rings.end());
    auto all = find_crossings(loops);
    ASSERT_EQ(all.size(), 3u);
    EXPECT_EQ(all[0].loop_a, 39u);
    EXPECT_EQ(all[0].loop_b, 40u);
    EXPECT_EQ(all[1].loop_a, 40u);
    EXPECT_EQ(all[1].loop_b, 41u);
    EXPECT_EQ(all[2].loop_a, 150u);
    EXPECT_EQ(all[2].loop_b, 150u);
    EXPECT_DOUBLE_EQ(all[2].point.x, 102.0);
    rings[40] = circle(0, 0, 30, 96);
    std::vector<std::span<const Vec2>> clean(rings.begin(), rings.end() - 1);
    EXPECT_TRUE(find_crossings(clean).empty());
}

TEST(Crossings, PullInwardSeparatesTouchingLoops) {
    std::vector<Vec2> a = {{0, 0}, {2, 2}, {0, 4}}, b = {{2, 2}, {4, 0}, {4, 4}};
    EXPECT_GT(pull_inward(a, {2, 2}, 0.01), 0.0);
    EXPECT_GT(pull_inward(b, {2, 2}, 0.01), 0.0);
    EXPECT_LT(a[1].x, 2.0);
    EXPECT_GT(b[0].x, 2.0);
    std::vector<std::span<const Vec2>> loops{a, b};
    EXPECT_TRUE(find_crossings(loops).empty());
}

}  // namespace
}  // namespace body
