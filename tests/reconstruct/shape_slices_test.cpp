// Shape-based slices between unlike contours (correspondence/shape_slices.h):
// where a structure's topology changes only between two slices (C shapes
// opening to opposite sides around a hole), a slice traced from the mean of
// the two slices' distance fields is inserted, so no band sweeps across the
// hole; bands between like contours get none.
#include "builder/correspondence/shape_slices.h"

#include <gtest/gtest.h>

#include <cmath>

#include "builder/contours/contour_stack.h"
#include "builder/slicing/mesh_slicer.h"
#include "tests/reconstruct/recon_test_util.h"

namespace body {
namespace {

using namespace body::test;

// An annulus about the origin (radii 0.65 and 1.35, `n` points per arc) with
// a gap of `gap` radians centred on direction `at`: one C-shaped contour.
std::vector<Vec2> c_shape(double at, double gap, int n = 96) {
    std::vector<Vec2> pts;
    const double from = at + 0.5 * gap, span = 2 * kPi - gap;
    for (int i = 0; i <= n; ++i) {
        const double t = from + span * i / n;
        pts.emplace_back(1.35 * std::cos(t), 1.35 * std::sin(t));
    }
    for (int i = n; i >= 0; --i) {
        const double t = from + span * i / n;
        pts.emplace_back(0.65 * std::cos(t), 0.65 * std::sin(t));
    }
    return pts;
}

// Smallest distance from the z axis of any point of the mesh's triangles
// between heights lo and hi (3 x 3 barycentric samples per triangle).
double nearest_to_axis(const Mesh& mesh, double lo, double hi) {
    double best = 1e300;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const Vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                   c = mesh.positions[mesh.indices[t + 2]];
        for (int i = 0; i <= 3; ++i)
            for (int j = 0; i + j <= 3; ++j) {
                const Vec3 p = a + (b - a) * (i / 3.0) + (c - a) * (j / 3.0);
                if (p.z >= lo && p.z <= hi) best = std::min(best, std::hypot(p.x, p.y));
            }
    }
    return best;
}

TEST(ShapeSlices, OppositeCShapesGetARingBetweenThem) {
    const std::vector<Vec2> lower = c_shape(0.5 * kPi, 0.3), upper = c_shape(-0.5 * kPi, 0.3);
    const std::vector<std::span<const Vec2>> a{lower}, b{upper};
    const std::vector<std::vector<Vec2>> mid = shape_mid_slice(a, b);
    ASSERT_EQ(mid.size(), 2u);  // the ring's outer boundary and its hole
    double outer = 0, hole = 0;
    for (const auto& ring : mid) {
        const double area = 0.5 * signed_area2(ring.data(), ring.size());
        (area > 0 ? outer : hole) += area;
    }
    EXPECT_NEAR(outer, kPi * 1.35 * 1.35, 0.1);
    EXPECT_NEAR(hole, -kPi * 0.65 * 0.65, 0.1);
}

TEST(ShapeSlices, LikeContoursGetNone) {
    const std::vector<Vec2> c = c_shape(0.5 * kPi, 0.3), c_turned = c_shape(0.55 * kPi, 0.3);
    const std::vector<Vec2> disc = circle(0, 0, 1), shifted = circle(0.3, 0.1, 0.8);
    const std::vector<Vec2> ring_out = circle(0, 0, 1.35), ring_in = reversed(circle(0, 0, 0.65));
    const std::vector<std::span<const Vec2>> cs{c}, ct{c_turned}, d{disc}, s{shifted}, ring{ring_out, ring_in};
    EXPECT_TRUE(shape_mid_slice(cs, ct).empty());
    EXPECT_TRUE(shape_mid_slice(d, s).empty());
    EXPECT_TRUE(shape_mid_slice(ring, ring).empty());
    EXPECT_TRUE(shape_mid_slice(cs, ring).empty());  // a hole opening into a notch: the ring is one end
}

// At branches (the interpolated build): a waisted contour below two discs
// gets the blended section half way; a disc over nothing beside a continuing
// one is an end (capped) and gets none; like contours get none; without
// `at_branches` none of them does.
TEST(ShapeSlices, BranchesGetASectionHalfWayAndEndsNone) {
    const std::vector<Vec2> left = circle(-0.7, 0, 0.6), right = circle(0.7, 0, 0.6);
    const std::vector<Vec2> waist = ellipse(0, 0, 1.4, 0.5, 0.0, 96);
    const std::vector<Vec2> far = circle(5, 0, 0.5), disc = circle(-0.7, 0, 0.62);
    const std::vector<std::span<const Vec2>> two{left, right}, one{waist}, with_far{disc, far}, alone{disc};
    const ShapeSlice branch = shape_slice_between(one, two, true);
    EXPECT_DOUBLE_EQ(branch.t, 0.5);
    EXPECT_TRUE(branch.at_branch);
    EXPECT_FALSE(branch.rings.empty());
    EXPECT_TRUE(shape_slice_between(one, two, false).rings.empty());
    EXPECT_TRUE(shape_slice_between(alone, with_far, true).rings.empty());
    EXPECT_TRUE(shape_slice_between(two, two, true).rings.empty());
}

// A toe: one disc below; above, the same disc with a round lobe joined to it
// by a thin neck. Three quarters up, the blended fields hold the lobe as a
// piece of its own (the neck, thinner than the lobe, is not there yet), two
// solids between slices of one each: that section is inserted.
TEST(ShapeSlices, APieceOfItsOwnBetweenSlicesGetsItsSection) {
    const std::vector<Vec2> body = circle(0, 0, 1.0, 128);
    std::vector<Vec2> toe;  // the disc, a neck 0.16 wide along +x to a lobe of radius 0.4 about (2, 0)
    const double neck = 0.08, a = std::asin(neck / 1.0), b = std::asin(neck / 0.4);
    for (int i = 0; i <= 120; ++i) {
        const double t = a + (2 * kPi - 2 * a) * i / 120;
        toe.emplace_back(std::cos(t), std::sin(t));
    }
    for (int i = 0; i <= 60; ++i) {
        const double t = kPi + b + (2 * kPi - 2 * b) * i / 60;  // round the lobe from its lower neck side
        toe.emplace_back(2.0 + 0.4 * std::cos(t), 0.4 * std::sin(t));
    }
    const std::vector<std::span<const Vec2>> lower{body}, upper{toe};
    const ShapeSlice s = shape_slice_between(lower, upper, true);
    ASSERT_FALSE(s.rings.empty());
    EXPECT_DOUBLE_EQ(s.t, 0.75);
    EXPECT_EQ(s.rings.size(), 2u);  // the disc with the neck's stub, and the lobe
    EXPECT_TRUE(shape_slice_between(lower, upper, false).rings.empty());
}

// Two slices: the band no longer sweeps across the hole (it came within 0.05
// of the axis before), the mesh stays closed and the C shapes stay on it.
TEST(ShapeSlices, BuildOfOppositeCShapesLeavesTheHoleOpen) {
    StackBuilder sb;
    sb.slice(0.0, {c_shape(0.5 * kPi, 1.2)}).slice(0.1, {c_shape(-0.5 * kPi, 1.2)});
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(sb.stack, rings);
        expect_good_structure(m, sb.stack, "");
        EXPECT_GT(nearest_to_axis(m.mesh, 0.0, 0.1), 0.55);
        bool mid = false;
        for (const Vec3& p : m.mesh.positions) mid = mid || std::abs(p.z - 0.05) < 1e-12;
        EXPECT_TRUE(mid) << "no vertex on the inserted slice";
    }
}

// Distance to a torus (R 1, r 0.35) turned 20 degrees about x.
double tilted_torus_distance(const Vec3& p) {
    const double c = std::cos(20 * kPi / 180), s = std::sin(20 * kPi / 180);
    const Vec3 q(p.x, p.y * c + p.z * s, -p.y * s + p.z * c);
    return std::hypot(std::hypot(q.x, q.y) - 1.0, q.z) - 0.35;
}

// The bench's tilted torus (bench/time_vs_vtk.py, coarser) sliced at 40
// planes along z: the slices either side of z = 0 are C shapes opening to
// opposite sides. Worst distance of the mesh to the torus: 0.49 before.
TEST(ShapeSlices, TiltedTorusStackStaysNearTheTorus) {
    const int nu = 96, nv = 40;
    std::vector<Vec3> pos;
    std::vector<uint32_t> idx;
    const double c = std::cos(20 * kPi / 180), s = std::sin(20 * kPi / 180);
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const double u = 2 * kPi * i / nu, v = 2 * kPi * j / nv;
            const double x = (1 + 0.35 * std::cos(v)) * std::cos(u), y = (1 + 0.35 * std::cos(v)) * std::sin(u),
                         z = 0.35 * std::sin(v);
            pos.emplace_back(x, y * c - z * s, y * s + z * c);
        }
    for (int i = 0; i < nu; ++i)
        for (int j = 0; j < nv; ++j) {
            const auto at = [&](int a, int b) { return uint32_t((a % nu) * nv + b % nv); };
            idx.insert(idx.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
    double lo = 1e300, hi = -1e300;
    for (const Vec3& p : pos) lo = std::min(lo, p.z), hi = std::max(hi, p.z);
    const std::vector<double> planes = evenly_spaced_planes(lo, hi, 40);
    auto stack = slice_mesh(pos, idx, 2, planes);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    const double gap = planes[1] - planes[0];
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(*stack, rings);
        expect_good_structure(m, *stack, "");
        EXPECT_EQ(m.components, 1u);
        double worst = 0;
        for (size_t t = 0; t + 2 < m.mesh.indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                const Vec3 a = m.mesh.positions[m.mesh.indices[t + k]],
                           b = m.mesh.positions[m.mesh.indices[t + (k + 1) % 3]];
                if (a.z >= planes.front() && a.z <= planes.back())
                    worst = std::max(worst, std::abs(tilted_torus_distance(0.5 * (a + b))));
            }
        RecordProperty(rings ? "interpolated" : "linear", std::to_string(worst / gap));
        EXPECT_LT(worst, gap) << "worst distance " << worst << " = " << worst / gap << " of a gap";
    }
}

// Two slices of natbrainlab's label 105 (bodygen contours, default options):
// two regions below meet one above, and the mid section inserted between them
// has holes that neither slice has. Caps closed them into cavities (and a flat
// sheet) of their own: 7 mesh pieces. Pieces that meet no input contour are
// removed: the region and the three small rings that end on a slice remain.
TEST(ShapeSlices, HolesOnlyTheMidSectionHasLeaveNoCavity) {
    auto stack = read_contour_stack(std::string(BODY_TEST_DATA_DIR) + "/stacks/inserted_cavity.contours.json");
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    for (int rings : {0, 3}) {
        SCOPED_TRACE(rings);
        const StructureMesh m = build_one(*stack, rings);
        expect_good_structure(m, *stack, "");
        EXPECT_EQ(m.components, 4u);
    }
}

}  // namespace
}  // namespace body
