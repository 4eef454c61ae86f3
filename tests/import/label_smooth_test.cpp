// Sub-voxel contours of label volumes: the scalar-field marching squares, the
// Gaussian blur and the importer's --label-smooth route.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "builder/import/gaussian_blur.h"
#include "builder/import/import.h"
#include "builder/import/label_volume.h"
#include "builder/import/ring_simplify.h"
#include "builder/slicing/marching_squares.h"
#include "tests/import/nifti_test_util.h"

namespace body {
namespace {

[[maybe_unused]] ::testing::Environment* const kCleanup = ::testing::AddGlobalTestEnvironment(new test::TempCleanup);

std::vector<uint8_t> random_blobs(std::mt19937& rng, size_t n) {
    std::vector<uint8_t> mask(n * n, 0);
    std::uniform_real_distribution<double> pos(1.0, n - 2.0), rad(0.7, 5.0);
    for (int k = 0; k < 6; ++k) {
        const double cx = pos(rng), cy = pos(rng), r = rad(rng);
        for (size_t y = 0; y < n; ++y)
            for (size_t x = 0; x < n; ++x)
                if (std::hypot(x - cx, y - cy) <= r) mask[y * n + x] ^= 1;
    }
    return mask;
}

// On a 0/1 field the scalar tracer is the mask tracer, point for point
// (diagonal contacts, holes and the one-pixel border included).
TEST(FieldIsolines, ZeroOneFieldEqualsTheMaskTracer) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 30; ++trial) {
        const size_t n = 20;
        const std::vector<uint8_t> mask = random_blobs(rng, n);
        std::vector<float> field(mask.begin(), mask.end());
        std::vector<std::vector<Vec2>> from_mask, from_field;
        trace_mask_boundaries(mask, n, n, from_mask);
        trace_field_isolines(field, n, n, 0.5f, from_field);
        ASSERT_FALSE(from_mask.empty());
        ASSERT_EQ(from_field, from_mask) << "trial " << trial;
    }
}

// Saddles: joined when the cell's mean is above the level, cut apart below;
// either way the rings stay simple.
TEST(FieldIsolines, SaddleFollowsTheCellMean) {
    std::vector<std::vector<Vec2>> rings;
    const std::vector<float> joined = {0.9f, 0.2f, 0.2f, 0.9f};  // mean 0.55 > 0.5: one region
    trace_field_isolines(joined, 2, 2, 0.5f, rings);
    EXPECT_EQ(rings.size(), 1u);
    EXPECT_TRUE(rings_are_simple(rings));
    const std::vector<float> apart = {0.6f, 0.1f, 0.1f, 0.6f};  // mean 0.35: two regions
    trace_field_isolines(apart, 2, 2, 0.5f, rings);
    EXPECT_EQ(rings.size(), 2u);
    EXPECT_TRUE(rings_are_simple(rings));
}

TEST(GaussianBlur, KeepsMassAndConstantsAndIsSymmetric) {
    const size_t size[3] = {21, 17, 19};
    std::vector<float> field(size[0] * size[1] * size[2], 0.0f);
    auto at = [&](size_t x, size_t y, size_t z) -> float& { return field[(z * size[1] + y) * size[0] + x]; };
    for (size_t z = 4; z < 15; ++z)
        for (size_t y = 4; y < 13; ++y)
            for (size_t x = 4; x < 17; ++x) at(x, y, z) = 1.0f;
    const double before = std::accumulate(field.begin(), field.end(), 0.0);
    const double sigma[3] = {1.0, 1.0, 1.0};
    gaussian_blur_3d(field, size, sigma);  // radius 3 < the 4-voxel padding
    EXPECT_NEAR(std::accumulate(field.begin(), field.end(), 0.0), before, 1e-3);
    EXPECT_NEAR(at(10, 8, 9), 1.0f, 1e-6);  // 3 voxels from every face: still constant
    EXPECT_NEAR(at(4, 8, 9), at(16, 8, 9), 1e-6);
    EXPECT_LT(at(4, 8, 9), 0.9f);  // the face voxel lost some to the outside
    EXPECT_GT(at(3, 8, 9), 0.1f);
}

// A box cut out of a larger volume and blurred alone gives the same floats as
// the larger volume's blur wherever every tap lies inside the box (one radius
// from its faces): what lets the importer blur the background once for all
// labels. The planes (90 x 70) are wider than the blur's span of rows, so the
// z pass is taken in pieces.
TEST(GaussianBlur, ABoxBlurredAloneMatchesTheWholeVolumesBlurInside) {
    const size_t big[3] = {90, 70, 24};
    std::vector<float> whole(big[0] * big[1] * big[2]);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> coin(0, 3);
    for (float& v : whole) v = coin(rng) == 0 ? 1.0f : 0.0f;
    for (size_t i = 0; i < big[0] * big[1]; ++i) whole[5 * big[0] * big[1] + i] = 0.0f;  // a zero plane
    const size_t lo[3] = {7, 5, 2}, box[3] = {75, 60, 20};
    std::vector<float> part(box[0] * box[1] * box[2]);
    for (size_t z = 0; z < box[2]; ++z)
        for (size_t y = 0; y < box[1]; ++y)
            for (size_t x = 0; x < box[0]; ++x)
                part[(z * box[1] + y) * box[0] + x] = whole[((z + lo[2]) * big[1] + y + lo[1]) * big[0] + x + lo[0]];
    const double sigma[3] = {2.0, 2.0, 1.0};
    gaussian_blur_3d(whole, big, sigma);
    gaussian_blur_3d(part, box, sigma);
    const size_t r[3] = {gaussian_radius(2.0), gaussian_radius(2.0), gaussian_radius(1.0)};
    size_t compared = 0, differ = 0;
    for (size_t z = r[2]; z + r[2] < box[2]; ++z)
        for (size_t y = r[1]; y + r[1] < box[1]; ++y)
            for (size_t x = r[0]; x + r[0] < box[0]; ++x, ++compared)
                differ += part[(z * box[1] + y) * box[0] + x] !=
                          whole[((z + lo[2]) * big[1] + y + lo[1]) * big[0] + x + lo[0]];
    EXPECT_GT(compared, 30000u);
    EXPECT_EQ(differ, 0u);
    // And near the box's faces the cut-off taps do show.
    EXPECT_NE(part[(10 * box[1] + 30) * box[0]], whole[((10 + lo[2]) * big[1] + 30 + lo[1]) * big[0] + lo[0]]);
}

// A ball of radius 9.3 voxels, off the grid: each slice's smoothed contour
// stays close to the true circle, far closer than the voxel staircase.
TEST(LabelSmooth, SphereSlicesFollowTheTrueCircle) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 32;
    const double cx = 15.6, cy = 16.2, cz = 15.4, radius = 9.3;
    std::vector<int16_t> data(32 * 32 * 32, 0);
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                if (std::hypot(x - cx, y - cy, z - cz) <= radius) data[(z * 32 + y) * 32 + x] = 3;
    const std::string path = test::temp_path("ball.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    auto worst_error = [&](double sigma) {
        ImportOptions o;
        o.tolerance = 0.0;
        o.label_smooth = sigma;
        auto stack = import_nifti_labels(path, o);
        EXPECT_TRUE(stack.ok()) << stack.error().message;
        double worst = 0.0;
        size_t slices = 0;
        for (const Slice& s : stack->slices) {
            const double dz = s.z - cz;
            if (radius * radius - dz * dz < 16.0) continue;  // near the poles a circle is a few voxels
            const double r = std::sqrt(radius * radius - dz * dz);
            EXPECT_EQ(s.contours.size(), 1u) << "z " << s.z;
            for (const Contour& c : s.contours)
                for (const Vec2& p : c.points) worst = std::max(worst, std::fabs(std::hypot(p.x - cx, p.y - cy) - r));
            ++slices;
        }
        EXPECT_GE(slices, 15u);
        return worst;
    };
    const double staircase = worst_error(0.0), smooth = worst_error(1.5);
    EXPECT_GT(staircase, 0.4);  // the voxel corners
    EXPECT_LT(smooth, 0.3);
    EXPECT_LT(smooth, 0.5 * staircase);
}

bool inside_rings(const std::vector<std::vector<Vec2>>& rings, const Vec2& p) {
    bool in = false;  // even-odd over every ring: holes included
    for (const auto& r : rings)
        for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
            if ((r[i].y > p.y) != (r[j].y > p.y) &&
                p.x < r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y))
                in = !in;
    return in;
}

// Two labels sharing an interface (halves of a ball, the cut plane oblique to
// the voxels, plus an interleaved comb): per label and slice the rings neither
// touch nor cross, the two labels' regions overlap by a sliver at most (none
// before simplification: the background term moves only boundaries against
// unlabelled voxels), and each label keeps its voxel volume within a few percent.
TEST(LabelSmooth, TwoLabelsGiveSimpleRingsAndKeepTheirVolumes) {
    test::VolumeSpec spec;
    spec.nx = 30, spec.ny = 28, spec.nz = 24;
    std::vector<int16_t> data(size_t(30) * 28 * 24, 0);
    size_t voxels[3] = {0, 0, 0};
    for (int z = 0; z < 24; ++z)
        for (int y = 0; y < 28; ++y)
            for (int x = 0; x < 30; ++x) {
                if (std::hypot(x - 14.5, y - 13.2, z - 11.7) > 10.0) continue;
                int16_t label = (x + 0.6 * y + 0.3 * z < 22.0) ? 1 : 2;
                if (y > 20 && x % 4 == 0) label = 3 - label;  // comb teeth of the other label
                data[(size_t(z) * 28 + y) * 30 + x] = label;
                ++voxels[label];
            }
    const std::string path = test::temp_path("halves.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    for (double tolerance : {0.0, 0.1}) {
        ImportOptions o;
        o.label_smooth = 1.0;
        o.tolerance = tolerance;
        auto stack = import_nifti_labels(path, o);
        ASSERT_TRUE(stack.ok()) << stack.error().message;
        ASSERT_EQ(stack->structures.size(), 2u);
        double area[3] = {0.0, 0.0, 0.0}, overlap = 0.0;
        for (const Slice& s : stack->slices) {
            std::vector<std::vector<Vec2>> rings[3];
            for (int label = 1; label <= 2; ++label) {
                for (const Contour& c : s.contours)
                    if (c.structure == "label_" + std::to_string(label)) rings[label].push_back(c.points);
                EXPECT_TRUE(rings_are_simple(rings[label])) << "z " << s.z << " label " << label;
                for (const auto& r : rings[label]) area[label] += 0.5 * signed_area2(r.data(), r.size());
            }
            constexpr double kStep = 0.1;  // overlap sampled on a 0.1-voxel grid
            for (double y = 0.0; y < 28.0; y += kStep)
                for (double x = 0.0; x < 30.0; x += kStep)
                    if (inside_rings(rings[1], {x, y}) && inside_rings(rings[2], {x, y})) overlap += kStep * kStep;
        }
        if (tolerance == 0.0) {
            EXPECT_LT(overlap, 0.05);  // a few grid samples on shared edges
        }
        EXPECT_LT(overlap, 0.005 * std::min(area[1], area[2]));
        for (int label = 1; label <= 2; ++label) {
            // Slices 1 voxel apart: the summed areas approximate the volume.
            EXPECT_NEAR(area[label], double(voxels[label]), 0.06 * voxels[label]) << "label " << label;
        }
    }
}

// Summed ring areas of one structure over every slice (slice gaps of 1 voxel:
// the volume in voxels), and its most rings on a slice among `slices`.
struct LabelOutcome {
    double area = 0.0;
    size_t most_rings = 0;
};
LabelOutcome label_outcome(const ContourStack& stack, const std::string& id, double z_lo, double z_hi) {
    LabelOutcome out;
    for (const Slice& s : stack.slices) {
        size_t rings = 0;
        for (const Contour& c : s.contours) {
            if (c.structure != id) continue;
            out.area += 0.5 * signed_area2(c.points.data(), c.points.size());
            rings += signed_area2(c.points.data(), c.points.size()) > 0.0;
        }
        if (s.z >= z_lo && s.z <= z_hi) out.most_rings = std::max(out.most_rings, rings);
    }
    return out;
}

// Thin labels enclosed by another label, the case the full blur erodes: a
// slab 2 voxels thick (label 2) and a dumbbell (label 3, two balls joined by a
// bridge 2 x 2 voxels thick), all inside label 1. At the default width each
// keeps its voxel volume within 10 %, the dumbbell stays one ring on the
// bridge's slices, and no two labels overlap.
TEST(LabelSmooth, ThinLabelsAndBridgesKeepTheirVolumeAndPieces) {
    test::VolumeSpec spec;
    spec.nx = 44, spec.ny = 36, spec.nz = 36;
    std::vector<int16_t> data(size_t(44) * 36 * 36, 0);
    size_t voxels[4] = {0, 0, 0, 0};
    auto at = [&](int x, int y, int z) -> int16_t& { return data[(size_t(z) * 36 + y) * 44 + x]; };
    for (int z = 3; z < 33; ++z)
        for (int y = 3; y < 33; ++y)
            for (int x = 3; x < 41; ++x) {
                int16_t label = 1;
                if (z >= 5 && z <= 30 && y >= 5 && y <= 10 && x >= 5 && x <= 38 && (z == 17 || z == 18)) label = 2;
                const bool ball =
                    std::hypot(x - 12.0, y - 22.0, z - 18.0) <= 5.0 || std::hypot(x - 31.0, y - 22.0, z - 18.0) <= 5.0;
                if (ball || (x > 12 && x < 31 && (y == 22 || y == 23) && (z == 17 || z == 18))) label = 3;
                at(x, y, z) = label;
            }
    for (int16_t l : data) ++voxels[l];
    const std::string path = test::temp_path("thin.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    ImportOptions o;
    o.label_smooth = 2.0;  // the CLI's default
    o.tolerance = 0.1;
    auto stack = import_nifti_labels(path, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->structures.size(), 3u);
    for (int label = 1; label <= 3; ++label) {
        const LabelOutcome r = label_outcome(*stack, "label_" + std::to_string(label), 17.0, 18.0);
        EXPECT_NEAR(r.area, double(voxels[label]), 0.10 * voxels[label]) << "label " << label;
        if (label == 3) {
            EXPECT_EQ(r.most_rings, 1u) << "the bridge broke";
        }
    }
    double overlap = 0.0;
    for (const Slice& s : stack->slices) {
        std::vector<std::vector<Vec2>> rings[4];
        for (const Contour& c : s.contours) rings[c.structure.back() - '0'].push_back(c.points);
        constexpr double kStep = 0.1;
        for (double y = 0.0; y < 36.0; y += kStep)
            for (double x = 0.0; x < 44.0; x += kStep) {
                int in = 0;
                for (int label = 1; label <= 3; ++label) in += inside_rings(rings[label], {x, y});
                if (in > 1) overlap += kStep * kStep;
            }
    }
    EXPECT_LT(overlap, 0.005 * double(voxels[2]));
}

// A square ring of side `side` at (x, y): inside on the left (counter-clockwise).
std::vector<Vec2> square(double x, double y, double side) {
    return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}};
}

// The islands of a label's rings: groups joined across adjacent slices
// (solids with solids, holes with holes) under the volume limit are dropped,
// the rest kept whole; a label whose groups are all small keeps its largest.
TEST(LabelSmooth, SmallIslandsOfRingsDropTheLargestAndRealPartsStay) {
    using Traced = std::vector<std::pair<size_t, std::vector<std::vector<Vec2>>>>;
    Traced traced;
    for (size_t k = 10; k < 16; ++k) {
        std::vector<std::vector<Vec2>> rings = {square(0, 0, 8), square(30, 0, 4)};  // two real parts
        if (k >= 12 && k < 15) rings.push_back(square(20, 20, 1.5));                 // an island: 3 slices x 2.25
        if (k >= 11 && k < 13) rings.push_back(square(7.5, 3, 1));                   // small, but meets the part's ring
        std::vector<Vec2> cavity = square(2, 2, 1);                                  // a hole of 1 x 1 on two slices
        std::reverse(cavity.begin(), cavity.end());
        if (k == 13 || k == 14) rings.push_back(cavity);
        traced.emplace_back(k, std::move(rings));
    }
    label_import::drop_small_islands(traced, 1, 20.0);
    size_t rings = 0, islands = 0, holes = 0, touching = 0;
    for (const auto& [k, slice] : traced) {
        for (const auto& r : slice) {
            ++rings;
            islands += r[0] == Vec2{20, 20};
            touching += r[0] == Vec2{7.5, 3};
            holes += signed_area2(r.data(), r.size()) < 0.0;
        }
    }
    EXPECT_EQ(islands, 0u) << "an island of 6.75 voxels kept";
    EXPECT_EQ(holes, 0u) << "a cavity of 2 voxels kept";
    EXPECT_EQ(touching, 2u) << "a small ring that meets its neighbour dropped";
    EXPECT_EQ(rings, 6u * 2u + 2u) << "a real part dropped";  // the 4 x 4 part: 96 voxels, kept

    Traced all_small = {{3, {square(0, 0, 1)}}, {4, {square(0.5, 0.5, 1), square(9, 9, 0.5)}}};
    label_import::drop_small_islands(all_small, 1, 20.0);
    EXPECT_EQ(all_small[0].second.size() + all_small[1].second.size(), 2u) << "the largest group must stay";
}

// Anisotropic voxels (1 x 1 x 3 mm, slices 3 mm apart): the blur is the same
// in millimetres on every axis, so a ball of radius 9 mm keeps its volume
// (a width of 2 voxels on the 3 mm axis would blur 6 mm there and shrink it).
TEST(LabelSmooth, AnisotropicVoxelsAreBlurredAlikeInMillimetres) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = 30, spec.nz = 12;
    spec.spacing[2] = 3.0;
    std::vector<int16_t> data(size_t(30) * 30 * 12, 0);
    size_t voxels = 0;
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 30; ++x)
                if (std::hypot(x - 14.6, y - 15.3, 3.0 * z - 16.4) <= 9.0)
                    data[(size_t(z) * 30 + y) * 30 + x] = 1, ++voxels;
    const std::string path = test::temp_path("aniso.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    ImportOptions o;
    o.label_smooth = 2.0;
    o.tolerance = 0.1;
    auto stack = import_nifti_labels(path, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    const LabelOutcome r = label_outcome(*stack, "label_1", 0.0, 0.0);
    EXPECT_NEAR(r.area, double(voxels), 0.05 * voxels);  // mm^2 per slice; one slice per voxel layer
    for (const Slice& s : stack->slices) {
        const double dz = s.z - 16.4, r2 = 81.0 - dz * dz;
        if (r2 < 25.0) continue;
        for (const Contour& c : s.contours)
            for (const Vec2& p : c.points)
                EXPECT_NEAR(std::hypot(p.x - 14.6, p.y - 15.3), std::sqrt(r2), 0.8) << "z " << s.z;
    }
}

TEST(LabelSmooth, OutOfRangeIsBadInput) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 4;
    std::vector<int16_t> data(64, 1);
    const std::string path = test::temp_path("cube.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    ImportOptions o;
    o.label_smooth = 4.5;
    auto stack = import_nifti_labels(path, o);
    ASSERT_FALSE(stack.ok());
    EXPECT_NE(stack.error().message.find("--label-smooth"), std::string::npos);
}

// A thin label's ragged edge: single voxels on top of a slab 2 voxels thick
// (label 2 inside label 1), each attached only to the slice below. Traced on
// the thin label's narrow blur each would be a ring of under a voxel face on
// its own slice, meeting nothing on the next slice: a mesh piece of its own.
// None is traced, and the slab keeps its volume within 10 %.
TEST(LabelSmooth, ThinLabelsRaggedEdgesBringNoSpecks) {
    test::VolumeSpec spec;
    spec.nx = 44, spec.ny = 36, spec.nz = 36;
    std::vector<int16_t> data(size_t(44) * 36 * 36, 0);
    size_t voxels[3] = {0, 0, 0};
    auto at = [&](int x, int y, int z) -> int16_t& { return data[(size_t(z) * 36 + y) * 44 + x]; };
    for (int z = 3; z < 33; ++z)
        for (int y = 3; y < 33; ++y)
            for (int x = 3; x < 41; ++x)
                at(x, y, z) = (z == 17 || z == 18) && y >= 5 && y <= 20 && x >= 5 && x <= 38 ? 2 : 1;
    for (int x = 7; x <= 35; x += 7)
        for (int y = 7; y <= 19; y += 4) at(x, y, 19) = 2;  // 20 specks, 4 % of the label
    for (int16_t l : data) ++voxels[l];
    const std::string path = test::temp_path("ragged.nii");
    test::write_nifti(path, spec, data, DT_INT16);
    ImportOptions o;
    o.label_smooth = 2.0;
    o.tolerance = 0.1;
    auto stack = import_nifti_labels(path, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    const LabelOutcome r = label_outcome(*stack, "label_2", 19.0, 19.0);
    EXPECT_EQ(r.most_rings, 0u) << "specks traced on the slice above the slab";
    EXPECT_NEAR(r.area, double(voxels[2]), 0.10 * voxels[2]);
}

}  // namespace
}  // namespace body
