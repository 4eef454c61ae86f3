// Small contours beside a large one near a structure's end (issue 23): a
// speck overlapping the neighbouring slice's contour branches into it (one
// component, nothing leaves the two slices' regions), a speck over nothing is
// capped within half the slice gap, and --min-area drops specks with a warning.
#include <gtest/gtest.h>

#include "builder/contours/validate.h"
#include "builder/pipeline/build_pipeline.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

// One labelled structure narrowing towards its top slice (z = 4), where a
// speck of 6 points and radius 0.05 sits beside the last large contour.
ContourStack speck_stack(double speck_x) {
    StackBuilder sb;
    sb.slice(0, {circle(0, 0, 1.0, 48)}, "organ")
        .slice(1, {circle(0, 0, 1.0, 48)}, "organ")
        .slice(2, {circle(0, 0, 0.95, 48)}, "organ")
        .slice(3, {circle(0, 0, 0.9, 48)}, "organ")
        .slice(4, {circle(-0.1, 0, 0.6, 40), circle(speck_x, 0, 0.05, 6)}, "organ");
    StructureInfo organ;
    organ.id = "organ";
    organ.name = "organ";
    sb.stack.structures.push_back(organ);
    return sb.stack;
}

StructureMesh build_one(const ContourStack& stack, const BuildOptions& options) {
    auto built = build_structures(stack, options, "speck");
    EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
    if (!built.ok() || built->size() != 1) return {};
    return std::move(built->front());
}

// Distance in x-y from `p` to the region inside a circle.
double to_disk(const Vec2& p, const Vec2& centre, double r) { return std::max(0.0, glm::length(p - centre) - r); }

TEST(SmallContours, SpeckOverTheSliceBelowBranchesIntoItWithoutASpike) {
    for (double x : {0.75, 0.88}) {  // inside the contour below, and half over its edge
        for (int rings : {0, 3}) {
            SCOPED_TRACE("speck at x=" + std::to_string(x) + ", rings " + std::to_string(rings));
            const ContourStack stack = speck_stack(x);
            BuildOptions options;
            options.interpolate = rings;
            const StructureMesh s = build_one(stack, options);
            expect_good_structure(s, stack, "organ");
            EXPECT_EQ(s.components, 1u);
            // Between the last two slices and on the cap above, every vertex stays
            // over the union of the two slices' regions (the polygons lie inside
            // their circles); no spike leaves it. The interpolated curves may bulge
            // past it, by at most 5 % of the slice gap.
            double worst = 0.0;
            for (const Vec3& p : s.mesh.positions) {
                if (p.z <= 3.0) continue;
                const Vec2 q(p);
                worst = std::max(
                    worst, std::min({to_disk(q, {0, 0}, 0.9), to_disk(q, {-0.1, 0}, 0.6), to_disk(q, {x, 0}, 0.05)}));
            }
            EXPECT_LE(worst, rings ? 0.05 : 1e-9);
            // Nothing goes further past the last slice than half the slice gap.
            EXPECT_LE(mesh_bounds(s.mesh.positions).max.z, 4.5);
        }
    }
}

TEST(SmallContours, SpeckOverNothingIsCappedWithinHalfTheSliceGap) {
    const ContourStack stack = speck_stack(1.2);  // beyond the slice below's contour (r 0.9)
    const StructureMesh s = build_one(stack, BuildOptions{});
    expect_good_structure(s, stack, "organ", false);
    EXPECT_EQ(s.components, 2u);  // the data says nothing joins it to the body
    double lo = 1e300, hi = -1e300;
    for (const Vec3& p : s.mesh.positions)
        if (p.x > 1.1) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
    EXPECT_GE(lo, 3.5);
    EXPECT_LE(hi, 4.5);
    EXPECT_LT(lo, 4.0);  // it has a thickness
}

TEST(SmallContours, MinAreaDropsSpecksWithAWarning) {
    ContourStack stack = speck_stack(1.2);
    RepairOptions options;
    options.min_area = 0.01;  // the speck's area is about 0.0065, the smallest other 1.13
    RepairLog log;
    ASSERT_TRUE(validate_contour_stack(stack, "speck.contours.json", options, log).ok());
    EXPECT_EQ(log.counts["small"], 1u);
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_NE(log.lines[0].find("speck.contours.json: slice 4 contour 1: at (1.25, 0): dropped a contour of area"),
              std::string::npos)
        << log.lines[0];
    EXPECT_EQ(stack.slices[4].contours.size(), 1u);

    BuildOptions build;
    build.repair.min_area = 0.01;
    const StructureMesh s = build_one(speck_stack(1.2), build);
    EXPECT_TRUE(s.closed_manifold);
    EXPECT_EQ(s.components, 1u);

    // Below the threshold nothing is dropped.
    ContourStack kept = speck_stack(1.2);
    RepairLog none;
    options.min_area = 0.005;
    ASSERT_TRUE(validate_contour_stack(kept, "speck.contours.json", options, none).ok());
    EXPECT_EQ(none.counts.count("small"), 0u);
    EXPECT_EQ(kept.slices[4].contours.size(), 2u);
}

}  // namespace
}  // namespace body
