// End caps that reach into the gap (caps/end_height.h): a solid whose ends
// fall between slices is closed by domes as high as the bands' slope says,
// so the whole mesh, caps included, stays near the true surface; the mesh
// stays a closed outward manifold without self-intersections and every traced
// point stays on it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "builder/caps/end_height.h"
#include "builder/pipeline/build_pipeline.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

// Largest |distance| of the mesh's surface (6 x 6 barycentric samples per
// triangle) to a surface given by its signed distance: all of it, caps included.
double worst_distance(const Mesh& mesh, const std::function<double(const Vec3&)>& distance) {
    double worst = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                   c = mesh.positions[mesh.indices[t + 2]];
        for (int i = 0; i <= 6; ++i)
            for (int j = 0; i + j <= 6; ++j)
                worst = std::max(worst, std::abs(distance(a + (b - a) * (i / 6.0) + (c - a) * (j / 6.0))));
    }
    return worst;
}

// A sphere of radius 1 about `centre` sliced at `slices` heights from
// centre.z + lo to centre.z + hi, `points` per contour (counter-clockwise).
void add_sphere(StackBuilder& sb, const Vec3& centre, double lo, double hi, int slices, int points) {
    for (int k = 0; k < slices; ++k) {
        const double z = lo + (hi - lo) * k / (slices - 1), r = std::sqrt(1 - z * z);
        std::vector<Vec2> ring;
        for (int i = 0; i < points; ++i) {
            const double t = 2 * kPi * (i + 0.37 * k) / points;
            ring.emplace_back(centre.x + r * std::cos(t), centre.y + r * std::sin(t));
        }
        sb.slice(centre.z + z, {ring});
    }
}

double highest(const Mesh& mesh) {
    double z = -1e300;
    for (const Vec3& p : mesh.positions) z = std::max(z, p.z);
    return z;
}

// Slices 0.2133 apart from -0.96 to 0.96: each pole lies 0.04 (0.19 of a gap)
// past the last slice. A dome of a fixed 0.45 gap would overshoot the pole by
// 0.056 (0.26 of a gap); the slope puts the tip within a tenth of a gap. The
// linear build's worst point is then the chord of the cap's flat triangulation
// through the pole, left at the slice's height (0.19 of a gap); the
// interpolated build lifts its domes' chords (caps.h), which must bring the
// whole mesh within a tenth of a gap (0.07; flat chords gave 0.19).
TEST(EndCaps, SpherePolesBetweenSlicesAreReachedFromTheSlope) {
    StackBuilder sb;
    add_sphere(sb, Vec3(0.0), -0.96, 0.96, 10, 96);
    const double gap = 1.92 / 9;
    const auto sphere = [](const Vec3& p) { return glm::length(p) - 1.0; };
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(sb.stack, rings);
        expect_good_structure(m, sb.stack, "");
        EXPECT_EQ(m.components, 1u);
        EXPECT_NEAR(highest(m.mesh), 1.0, 0.1 * gap);
        const double worst = worst_distance(m.mesh, sphere);
        RecordProperty(rings ? "interpolated" : "linear", std::to_string(worst / gap));
        EXPECT_LT(worst, (rings ? 0.1 : 0.2) * gap)
            << "worst distance " << worst << " = " << worst / gap << " of a gap";
    }
}

// A sphere of radius 0.8 beside a longer column, in one structure: its poles
// lie 0.05 (0.2 of a gap) past its last slices, inside the stack's range.
// Interpolated, the lifted chords keep it within a tenth of a gap (0.06; flat
// chords gave 0.13).
TEST(EndCaps, PieceBeginningAndEndingBetweenSlicesInsideTheStack) {
    StackBuilder sb;
    const double gap = 0.25, radius = 0.8;
    for (int k = 0; k < 13; ++k) {
        const double z = -1.5 + gap * k;
        std::vector<std::vector<Vec2>> rings{circle(4.0, 0.0, 1.0, 64)};
        if (std::abs(z) < radius) rings.push_back(circle(0.0, 0.0, std::sqrt(radius * radius - z * z), 96));
        sb.slice(z, rings, "a");
    }
    sb.stack.structures.push_back({"a", "A", Vec3(0.8)});
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(sb.stack, rings);
        expect_good_structure(m, sb.stack, "a");
        EXPECT_EQ(m.components, 2u);
        double worst = 0, top = -1e300, bottom = 1e300;
        for (size_t t = 0; t + 2 < m.mesh.indices.size(); t += 3) {
            const Vec3 a = m.mesh.positions[m.mesh.indices[t]], b = m.mesh.positions[m.mesh.indices[t + 1]],
                       c = m.mesh.positions[m.mesh.indices[t + 2]];
            if (a.x > 2.0) continue;  // the column
            for (const Vec3& p : {a, b, c, (a + b + c) / 3.0}) {
                worst = std::max(worst, std::abs(glm::length(p) - radius));
                top = std::max(top, p.z);
                bottom = std::min(bottom, p.z);
            }
        }
        RecordProperty(rings ? "interpolated" : "linear", std::to_string(worst / gap));
        EXPECT_LT(worst, (rings ? 0.1 : 0.2) * gap) << worst / gap << " of a gap";
        EXPECT_NEAR(top, radius, 0.1 * gap);
        EXPECT_NEAR(bottom, -radius, 0.1 * gap);
    }
}

// The ending ring and two 0.5 and 1 below it, radii 1 + k s / 2: a cone of
// slope s closes at 1 / s past the slice (a double root of the quadratic
// area), a cylinder (s = 0) never does and gets the limit.
TEST(EndCaps, HeightFromTheAreasOfTheSlicesBelowStopsAtTheLimit) {
    const int n = 64;
    std::vector<Vec2> xy;
    std::vector<uint32_t> ids;
    for (int i = 0; i < n; ++i) {
        xy.emplace_back(std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n));
        ids.push_back(uint32_t(i));
    }
    for (double slope : {1.0, 0.25, 0.0}) {
        SCOPED_TRACE(slope);
        std::vector<Vec3> p;
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < n; ++i)
                p.emplace_back((1 + 0.5 * k * slope) * Vec3(xy[size_t(i)], 0.0) + Vec3(0, 0, -0.5 * k));
        std::vector<uint32_t> triangles;
        for (uint32_t k = 0; k < 2; ++k)
            for (uint32_t i = 0; i < uint32_t(n); ++i) {
                const uint32_t j = (i + 1) % n, a = k * n, b = (k + 1) * n;
                triangles.insert(triangles.end(), {a + i, b + i, b + j, a + i, b + j, a + j});
            }
        RungPartners partners;
        rung_partners(p, triangles, partners);
        const EndHeight end = end_height(xy, ids, p, partners, true, 5.0);
        if (slope > 0) {
            EXPECT_TRUE(end.closing);
            // A double root: the partner means' small shrink (a tenth of a
            // percent) moves it by about a tenth.
            EXPECT_NEAR(end.height, 1 / slope, 0.15 / slope);
            EXPECT_DOUBLE_EQ(end_height(xy, ids, p, partners, true, 0.3).height, 0.3);  // the limit
        } else {
            EXPECT_FALSE(end.closing);
            EXPECT_DOUBLE_EQ(end.height, 5.0);
        }
        // Seen from the other side nothing is above: no slope, the limit.
        EXPECT_FALSE(end_height(xy, ids, p, partners, false, 5.0).closing);
    }
}

}  // namespace
}  // namespace body
