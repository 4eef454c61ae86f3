// Nested contours: correspondence by material regions (a solid ring links to
// its own partner, not to every ring around it), the region overlap areas, and
// stacks of concentric rings built into one closed shell per solid ring.
#include <gtest/gtest.h>

#include "builder/contours/validate.h"
#include "builder/correspondence/grouping.h"
#include "builder/correspondence/material_regions.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

std::vector<Vec2> square(double half, double cx = 0) {
    return {{cx - half, -half}, {cx + half, -half}, {cx + half, half}, {cx - half, half}};
}

struct Slice2 {
    std::vector<std::vector<Vec2>> contours;
    std::vector<PolygonSpan> spans;
    Nesting nesting;
    explicit Slice2(std::vector<std::vector<Vec2>> c) : contours(std::move(c)) {
        spans.assign(contours.begin(), contours.end());
        nesting = compute_nesting(spans);
    }
    NestedContours nested() const { return {spans, nesting.parent}; }
};

// Concentric rings of radius 1 + 0.5 k, k = 0..n-1 (ring n-1 is the outermost).
std::vector<std::vector<Vec2>> rings(int n, double dx = 0, int points = 32) {
    std::vector<std::vector<Vec2>> out;
    for (int k = 0; k < n; ++k) out.push_back(circle(dx, 0, 1 + 0.5 * k, points));
    return out;
}

TEST(MaterialRegions, OverlapIsTheAreaBetweenAContourAndItsChildren) {
    // Nested squares of half size 4 (solid), 3 (hole), 2 (solid island), 1 (hole in it).
    const Slice2 lower({square(4), square(3), square(2), square(1)});
    const Slice2 same({square(4), square(3), square(2), square(1)});
    const std::vector<RegionOverlap> r = region_overlaps(lower.nested(), same.nested());
    ASSERT_EQ(r.size(), 4u);
    const double areas[4] = {64 - 36, 36 - 16, 16 - 4, 4};
    for (uint32_t k = 0; k < 4; ++k) {
        EXPECT_EQ(r[k].link, (ContourLink{k, k}));
        EXPECT_NEAR(r[k].area, areas[k], 1e-9);
    }
    // Above, one solid square: both solids' material lies under it (a 2:1
    // branch); the holes end.
    const Slice2 solid({square(4)});
    EXPECT_EQ(correspond_nested(lower.nested(), solid.nested(), CorrespondenceMethod::Overlap),
              (std::vector<ContourLink>{{0, 0}, {2, 0}}));
    // Shifted by 0.5: the island's material (a 4x4 frame minus the 2x2 hole)
    // overlaps the shifted island's by inclusion-exclusion of the four squares:
    // 3.5x4 - 2x2 - 2x2 + 1.5x2.
    const Slice2 shifted({square(4, 0.5), square(3, 0.5), square(2, 0.5), square(1, 0.5)});
    bool found = false;
    for (const RegionOverlap& o : region_overlaps(lower.nested(), shifted.nested())) {
        if (o.link != ContourLink{2, 2}) continue;
        EXPECT_NEAR(o.area, 14.0 - 4 - 4 + 3, 1e-9);
        found = true;
    }
    EXPECT_TRUE(found);
}

TEST(MaterialRegions, EachRingLinksToItsOwnPartner) {
    for (const double dx : {0.0, 0.1}) {  // the same rings above, and shifted by a fifth of their spacing
        const Slice2 lower(rings(40)), upper(rings(40, dx));
        const std::vector<ContourLink> links =
            correspond_nested(lower.nested(), upper.nested(), CorrespondenceMethod::Overlap);
        ASSERT_EQ(links.size(), 40u) << "dx " << dx;
        for (uint32_t k = 0; k < 40; ++k) EXPECT_EQ(links[k], (ContourLink{k, k})) << "dx " << dx;
        // The whole-contour overlap links every solid to every other solid (the
        // one branching group of all rings that made this stack take minutes).
        std::vector<PolygonSpan> solids_lower, solids_upper;
        for (size_t k = 1; k < 40; k += 2)
            solids_lower.push_back(lower.spans[k]), solids_upper.push_back(upper.spans[k]);
        EXPECT_EQ(correspond_contours(solids_lower, solids_upper, CorrespondenceMethod::Overlap).size(), 20u * 20u);
    }
}

TEST(MaterialRegions, FourHundredRingsMakeOneBandEach) {
    const Slice2 lower(rings(400)), upper(rings(400));
    const std::vector<ContourLink> links =
        correspond_nested(lower.nested(), upper.nested(), CorrespondenceMethod::Overlap);
    const std::vector<LinkGroup> groups = group_links(links, 400, 400);
    ASSERT_EQ(groups.size(), 400u);
    for (const LinkGroup& g : groups) {
        ASSERT_EQ(g.lower.size(), 1u);
        ASSERT_EQ(g.upper.size(), 1u);
        EXPECT_EQ(g.lower[0], g.upper[0]);
    }
}

// Rings 0..n-1 alternate hole and solid from the outside in; n = 5: two tubes
// and a solid core, each a closed outward shell of its own.
TEST(MaterialRegions, ConcentricRingsBuildOneShellPerSolidRing) {
    for (const double dx : {0.0, 0.1}) {
        StackBuilder b;
        for (int s = 0; s < 3; ++s) b.slice(2.0 * s, rings(5, s == 1 ? dx : 0.0));
        BuildOptions o;
        auto r = build_structures(b.stack, o, "rings.contours.json");
        ASSERT_TRUE(r.ok()) << r.error().message;
        ASSERT_EQ(r->size(), 1u);
        expect_good_structure((*r)[0], b.stack, "");
        EXPECT_EQ((*r)[0].components, 3u) << "dx " << dx;
        EXPECT_EQ((*r)[0].genus, 2) << "dx " << dx;  // two tubes, one core
    }
}

TEST(MaterialRegions, FourHundredRingsAndABranchBuildClosed) {
    StackBuilder b;
    const double far = 1 + 0.5 * 400 + 20;
    for (int s = 0; s < 3; ++s) {
        std::vector<std::vector<Vec2>> c = rings(400);
        if (s == 0)
            c.push_back(circle(far, 0, 8));
        else
            c.push_back(circle(far - 4, 0, 3)), c.push_back(circle(far + 4, 0, 3));
        b.slice(2.0 * s, std::move(c), "");
    }
    BuildOptions o;
    auto r = build_structures(b.stack, o, "rings.contours.json");
    ASSERT_TRUE(r.ok()) << r.error().message;
    ASSERT_EQ(r->size(), 2u);  // the rings' nest and the branching piece
    size_t components = 0;
    for (const StructureMesh& m : *r) {
        EXPECT_TRUE(m.closed_manifold) << m.id;
        EXPECT_GT(m.volume, 0.0) << m.id;
        components += m.components;
    }
    EXPECT_EQ(components, 200u + 1u);
}

}  // namespace
}  // namespace body
