// Branch constructions at blended heights (chord_heights.h): a partition
// chord goes where the two slices' distance fields blend to zero instead of
// staying level at one height, and
// the mesh stays a closed outward manifold without self-intersections that
// keeps every traced contour.
#include <gtest/gtest.h>

#include <cmath>

#include "builder/branching/chord_heights.h"
#include "builder/pipeline/build_pipeline.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

TEST(ChordHeights, ZeroOfTheBlendedDistancesWithinTheClamp) {
    const std::vector<Vec2> single = circle(0, 0, 1.0, 256);
    const std::vector<Vec2> left = circle(-0.5, 0, 0.3, 256), right = circle(0.5, 0, 0.3, 256);
    const std::span<const Vec2> branches[] = {left, right};
    // Between the branches (d_s 1, d_b 0.2): 1 / 1.2 of the way to them;
    // next to the single loop (d_s 0.01): the clamp's 0.05.
    std::vector<Vec3> positions{Vec3(7, 7, 7), Vec3(0, 0, 0), Vec3(0, 0.99, 0)};
    blend_chord_heights(positions, 1, single, 2.0, branches, 4.0, 0.05, 0.95);
    EXPECT_EQ(positions[0].z, 7.0);  // before `first`: untouched
    EXPECT_NEAR(positions[1].z, 2.0 + 2.0 * (1.0 / 1.2), 1e-3);
    EXPECT_NEAR(positions[2].z, 2.0 + 2.0 * 0.05, 1e-12);
}

// A solid disc with a hole near its rim on slice 0; on slice 1 the hole has
// opened through the rim: the notch is the hole's inner half (a little wider)
// with straight sides out to the rim. The rim between hole and mouth is 0.1
// thick and the mouth 0.64 wide, so the rim ends near slice 0 (the blend's
// zero at about 0.14 of the gap), not at mid-slice or higher.
TEST(BlendedHeights, OpenHoleRimEndsWhereTheDistancesSay) {
    const double w = 0.4, xr = std::sqrt(1 - w * w);
    std::vector<Vec2> notched;
    for (int i = 0; i <= 120; ++i) {  // the rim, counter-clockwise from the notch's upper side
        const double a0 = std::asin(w), a1 = 2 * kPi - std::asin(w);
        const double t = a0 + (a1 - a0) * i / 120;
        notched.emplace_back(std::cos(t), std::sin(t));
    }
    for (int i = 1; i < 6; ++i) notched.emplace_back(xr - (xr - 0.6) * i / 6, -w);
    for (int i = 0; i <= 24; ++i) {  // the notch's inner end round the hole's inner half, clockwise
        const double t = -kPi / 2 - kPi * i / 24;
        notched.emplace_back(0.6 + w * std::cos(t), w * std::sin(t));
    }
    for (int i = 1; i < 6; ++i) notched.emplace_back(0.6 + (xr - 0.6) * i / 6, w);
    StackBuilder sb;
    sb.slice(0.0, {circle(0, 0, 1.0, 128), reversed(circle(0.6, 0, 0.3, 48))});
    sb.slice(1.0, {notched});
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(sb.stack, rings);
        expect_good_structure(m, sb.stack, "");
        EXPECT_EQ(m.components, 1u);
        // The rim's top between hole and mouth: vertices off both slices there.
        size_t rim = 0;
        for (const Vec3& p : m.mesh.positions) {
            if (!(p.z > 1e-9 && p.z < 1 - 1e-9) || p.x < 0.88 || std::abs(p.y) > 0.1) continue;
            ++rim;
            EXPECT_LT(p.z, 0.3) << p.x << " " << p.y;
        }
        EXPECT_GT(rim, 0u);
    }
}

}  // namespace
}  // namespace body
