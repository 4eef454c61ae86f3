// The dome cap on its own: a height field over the flat cap whose boundary is
// exactly the region's loops, one apex per triangle on small caps and about
// the flat cap's triangle count on large ones (dome_groups.h).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "builder/caps/caps.h"
#include "builder/caps/dome_groups.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

struct Cap {
    std::vector<Vec3> positions;
    std::vector<uint32_t> triangles;
    size_t rim = 0;  // positions before the dome's apexes
};

std::vector<Vec2> wavy_ring(double r, double wave, size_t n, bool cw) {
    std::vector<Vec2> ring(n);
    for (size_t i = 0; i < n; ++i) {
        const double a = 2 * M_PI * double(i) / double(n) * (cw ? -1 : 1);
        const double radius = r + wave * std::sin(37 * a);
        ring[i] = Vec2(radius * std::cos(a), radius * std::sin(a));
    }
    return ring;
}

Cap make_cap(const std::vector<std::vector<Vec2>>& loops, CapStyle style, bool up, double height,
             bool lift_chords = false) {
    Cap cap;
    std::vector<std::span<const Vec2>> spans;
    std::vector<std::vector<uint32_t>> ids(loops.size());
    std::vector<std::span<const uint32_t>> id_spans;
    for (size_t k = 0; k < loops.size(); ++k) {
        spans.emplace_back(loops[k]);
        for (const Vec2& p : loops[k]) {
            ids[k].push_back(uint32_t(cap.positions.size()));
            cap.positions.emplace_back(p.x, p.y, 1.0);
        }
        id_spans.emplace_back(ids[k]);
    }
    cap.rim = cap.positions.size();
    EXPECT_TRUE(
        build_cap(spans, id_spans, 1.0, up, style, height, cap.positions, cap.triangles, false, lift_chords).ok());
    return cap;
}

// Every triangle seen from the side it faces is counter-clockwise in x-y (a
// height field: nothing folds), they cover the region's area once, and the
// cap's open edges are exactly the loops' edges, once each.
void expect_height_field_over(const Cap& cap, const std::vector<std::vector<Vec2>>& loops, bool up, double area) {
    double covered = 0;
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t < cap.triangles.size(); t += 3) {
        const Vec3 a = cap.positions[cap.triangles[t]], b = cap.positions[cap.triangles[t + 1]],
                   c = cap.positions[cap.triangles[t + 2]];
        const double s = ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x)) * (up ? 1 : -1);
        ASSERT_GT(s, 0.0) << "triangle " << t / 3 << " folds";
        covered += s / 2;
        for (int k = 0; k < 3; ++k) edges[{cap.triangles[t + k], cap.triangles[t + (k + 1) % 3]}]++;
    }
    EXPECT_NEAR(covered, area, 1e-9 * area);
    size_t open = 0;
    for (const auto& [e, n] : edges) {
        EXPECT_EQ(n, 1) << "edge used twice the same way";
        if (!edges.count({e.second, e.first})) {
            ++open;
            EXPECT_LT(e.first, cap.rim);
            EXPECT_LT(e.second, cap.rim);
        }
    }
    size_t loop_points = 0;
    for (const auto& l : loops) loop_points += l.size();
    EXPECT_EQ(open, loop_points);
}

TEST(DomeCap, SmallCapHasOneApexPerFlatTriangle) {
    const std::vector<std::vector<Vec2>> loops{circle(0, 0, 10, 40), circle(3, 0, 2, 12)};
    const Cap flat = make_cap(loops, CapStyle::Flat, true, 1.0);
    const Cap dome = make_cap(loops, CapStyle::Dome, true, 1.0);
    EXPECT_EQ(dome.triangles.size(), 3 * flat.triangles.size());
    EXPECT_EQ(dome.positions.size() - dome.rim, flat.triangles.size() / 3);
}

// 20,000 + 6,000 points: the dome stays within 1.5x the flat cap's
// triangles (one apex per one to seven of them here), still rises to its height, and is a height field over the
// region (facing up and facing down).
TEST(DomeCap, LargeCapNearTheFlatCapsSize) {
    const std::vector<std::vector<Vec2>> loops{wavy_ring(100, 3, 20000, false), wavy_ring(40, 2, 6000, true)};
    const double area = (std::abs(signed_area2(loops[0].data(), loops[0].size())) -
                         std::abs(signed_area2(loops[1].data(), loops[1].size()))) /
                        2;
    const Cap flat = make_cap(loops, CapStyle::Flat, true, 2.0);
    for (bool up : {true, false}) {
        const Cap dome = make_cap(loops, CapStyle::Dome, up, 2.0);
        const size_t flat_count = flat.triangles.size() / 3, count = dome.triangles.size() / 3;
        const size_t apexes = dome.positions.size() - dome.rim;
        EXPECT_EQ(count, flat_count + 2 * apexes);  // a group of k flat triangles is a fan of k + 2
        EXPECT_LT(double(count), 1.5 * double(flat_count));
        EXPECT_GE(apexes, flat_count / 16);
        EXPECT_GE(apexes, kDomeSamples / 2);
        double highest = 0;
        for (size_t i = dome.rim; i < dome.positions.size(); ++i) {
            const double h = (dome.positions[i].z - 1.0) * (up ? 1 : -1);
            EXPECT_GE(h, 0.0);
            EXPECT_LE(h, 2.0 + 1e-12);
            highest = std::max(highest, h);
        }
        EXPECT_NEAR(highest, 2.0, 1e-12);
        expect_height_field_over(dome, loops, up, area);
    }
}

// Lifted chords (caps.h): the dome is still a height field whose open edges
// are the loops' edges, and no other edge stays at the slice's height (flat
// chords did: every edge between two fans). A long thin region, whose
// ear-clipped chords run across it, and a region with a hole; both sides.
TEST(DomeCap, LiftedChordsLeaveOnlyTheLoopsAtTheSliceHeight) {
    const std::vector<std::vector<std::vector<Vec2>>> regions{{ellipse(0, 0, 30, 2, 0.3, 80)},
                                                              {circle(0, 0, 10, 40), circle(3, 0, 2, 12)}};
    for (const auto& loops : regions)
        for (bool up : {true, false}) {
            SCOPED_TRACE(loops.size());
            double area = std::abs(signed_area2(loops[0].data(), loops[0].size())) / 2;
            for (size_t k = 1; k < loops.size(); ++k)
                area -= std::abs(signed_area2(loops[k].data(), loops[k].size())) / 2;
            const Cap flat_chords = make_cap(loops, CapStyle::Dome, up, 1.0);
            const Cap dome = make_cap(loops, CapStyle::Dome, up, 1.0, true);
            EXPECT_GT(dome.positions.size(), flat_chords.positions.size());
            expect_height_field_over(dome, loops, up, area);
            size_t rim_edges = 0;
            for (size_t t = 0; t < dome.triangles.size(); t += 3)
                for (int k = 0; k < 3; ++k) {
                    const uint32_t a = dome.triangles[t + k], b = dome.triangles[t + (k + 1) % 3];
                    if (dome.positions[a].z != 1.0 || dome.positions[b].z != 1.0) continue;
                    ++rim_edges;
                    EXPECT_LT(a, dome.rim);
                    EXPECT_LT(b, dome.rim);
                }
            for (size_t i = dome.rim; i < dome.positions.size(); ++i) {
                const double h = (dome.positions[i].z - 1.0) * (up ? 1 : -1);
                EXPECT_GT(h, 0.0);
                EXPECT_LE(h, 1.0 + 1e-12);
            }
            size_t loop_points = 0;
            for (const auto& l : loops) loop_points += l.size();
            EXPECT_EQ(rim_edges, loop_points);  // each loop edge once, nothing else
        }
}

}  // namespace
}  // namespace body
