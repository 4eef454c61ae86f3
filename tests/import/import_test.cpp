// Import tests: marching squares, ring simplification, label tables, synthetic
// NIfTI label volumes (written with niftilib here) and the real RT-STRUCT.
#include "builder/import/import.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "builder/import/label_table.h"
#include "builder/import/ring_simplify.h"
#include "builder/slicing/marching_squares.h"
#include "shared/atomic_file.h"
#include "tests/import/nifti_test_util.h"

namespace body {
namespace {

[[maybe_unused]] ::testing::Environment* const kCleanup = ::testing::AddGlobalTestEnvironment(new test::TempCleanup);

double area(const std::vector<Vec2>& r) { return 0.5 * signed_area2(r.data(), r.size()); }

// ---------------------------------------------------------------- marching squares

std::vector<std::vector<Vec2>> trace(const std::vector<std::string>& rows) {
    // rows[0] is y = 0; '#' inside.
    const size_t h = rows.size(), w = rows[0].size();
    std::vector<uint8_t> mask(w * h);
    for (size_t y = 0; y < h; ++y)
        for (size_t x = 0; x < w; ++x) mask[y * w + x] = rows[y][x] == '#';
    std::vector<std::vector<Vec2>> rings;
    trace_mask_boundaries(mask, w, h, rings);
    return rings;
}

TEST(MarchingSquares, SinglePixelIsAHalfVoxelDiamond) {
    auto rings = trace({"#"});
    ASSERT_EQ(rings.size(), 1u);
    EXPECT_EQ(rings[0].size(), 4u);
    EXPECT_DOUBLE_EQ(area(rings[0]), 0.5);
    for (const Vec2& p : rings[0]) EXPECT_DOUBLE_EQ(std::fabs(p.x) + std::fabs(p.y), 0.5);
}

TEST(MarchingSquares, AreaIsVoxelCountMinusHalfPerOuterPlusHalfPerHole) {
    auto rings = trace({"#####", "#####", "##.##", "#####"});
    ASSERT_EQ(rings.size(), 2u);
    std::sort(rings.begin(), rings.end(), [](auto& a, auto& b) { return area(a) > area(b); });
    EXPECT_DOUBLE_EQ(area(rings[0]), 20.0 - 0.5);             // outer, counter-clockwise
    EXPECT_DOUBLE_EQ(area(rings[1]), -0.5);                   // the hole, clockwise, around the one outside pixel
    EXPECT_DOUBLE_EQ(area(rings[0]) + area(rings[1]), 19.0);  // = the 19 inside pixels
}

TEST(MarchingSquares, DiagonalPixelsAreSeparateNonTouchingRings) {
    auto rings = trace({"#.", ".#"});
    ASSERT_EQ(rings.size(), 2u);
    EXPECT_TRUE(rings_are_simple(rings));
    double closest = 1e9;
    for (const Vec2& p : rings[0])
        for (const Vec2& q : rings[1]) closest = std::min(closest, glm::length(p - q));
    EXPECT_GE(closest, 0.7);
    // The complementary pattern inside a frame: the outside is 8-connected, so the
    // two diagonal outside pixels make one hole.
    auto framed = trace({"####", "##.#", "#.##", "####"});
    ASSERT_EQ(framed.size(), 2u);
    EXPECT_DOUBLE_EQ(area(framed[0]) + area(framed[1]), 14.0);
    EXPECT_TRUE(rings_are_simple(framed));
}

TEST(MarchingSquares, CheckerboardLabelsNeverOverlap) {
    // Two labels in a checkerboard: label a's region and label b's region share
    // only boundary points, so total area = a + b <= the union of the pixels.
    const size_t n = 6;
    std::vector<uint8_t> a(n * n), b(n * n);
    for (size_t y = 0; y < n; ++y)
        for (size_t x = 0; x < n; ++x) ((x + y) % 2 ? a : b)[y * n + x] = 1;
    std::vector<std::vector<Vec2>> ra, rb;
    trace_mask_boundaries(a, n, n, ra);
    trace_mask_boundaries(b, n, n, rb);
    double total = 0.0;
    for (auto& r : ra) total += area(r);
    for (auto& r : rb) total += area(r);
    EXPECT_DOUBLE_EQ(total, 36 * 0.5);  // every pixel a separate diamond
    EXPECT_TRUE(rings_are_simple(ra));
    EXPECT_TRUE(rings_are_simple(rb));
}

// ---------------------------------------------------------------- simplification

TEST(RingSimplify, RandomBlobsStayValidAndWithinTolerance) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 40; ++trial) {
        const size_t n = 24;
        std::vector<uint8_t> mask(n * n, 0);
        // A few random discs, some overlapping, some touching diagonally.
        std::uniform_real_distribution<double> pos(2.0, n - 3.0), rad(1.0, 5.0);
        for (int k = 0; k < 5; ++k) {
            const double cx = pos(rng), cy = pos(rng), r = rad(rng);
            for (size_t y = 0; y < n; ++y)
                for (size_t x = 0; x < n; ++x)
                    if (std::hypot(x - cx, y - cy) <= r) mask[y * n + x] ^= 1;
        }
        std::vector<std::vector<Vec2>> rings;
        trace_mask_boundaries(mask, n, n, rings);
        ASSERT_TRUE(rings_are_simple(rings)) << "trial " << trial;
        const auto original = rings;
        simplify_rings(rings, 0.5);
        ASSERT_EQ(rings.size(), original.size());
        EXPECT_TRUE(rings_are_simple(rings)) << "trial " << trial;
        for (size_t i = 0; i < rings.size(); ++i) {
            EXPECT_GE(rings[i].size(), 3u);
            EXPECT_LE(rings[i].size(), original[i].size());
            EXPECT_EQ(area(rings[i]) > 0, area(original[i]) > 0);
            EXPECT_NEAR(area(rings[i]), area(original[i]), 0.5 * static_cast<double>(original[i].size()));
        }
    }
}

TEST(RingSimplify, StaircaseBecomesAStraightEdge) {
    // A shallow staircase along a 40x20 right triangle.
    const size_t w = 40, h = 20;
    std::vector<uint8_t> mask(w * h, 0);
    for (size_t y = 0; y < h; ++y)
        for (size_t x = 0; x < w; ++x) mask[y * w + x] = 2 * y <= x;
    std::vector<std::vector<Vec2>> rings;
    trace_mask_boundaries(mask, w, h, rings);
    ASSERT_EQ(rings.size(), 1u);
    const size_t before = rings[0].size();
    simplify_rings(rings, 0.5);
    EXPECT_GT(before, 30u);
    EXPECT_LE(rings[0].size(), 8u);  // the minimum kept for any ring of 8 or more
}

// ---------------------------------------------------------------- label tables

TEST(LabelTable, MricronAalForm) {
    auto t = parse_label_table("1 Precentral_L 2001\r\n2 Precentral_R 2002\r\n\r\n", "aal.nii.txt");
    ASSERT_TRUE(t.ok()) << t.error().message;
    ASSERT_EQ(t->entries.size(), 2u);
    EXPECT_EQ(t->entries.at(1).name, "Precentral_L");
    EXPECT_FALSE(t->entries.at(1).color.has_value());
}

TEST(LabelTable, FslLutAndFreeSurferForms) {
    auto fsl = parse_label_table("# fsleyes\n3 1.0 0.5 0 Left Thalamus\n", "x.lut");
    ASSERT_TRUE(fsl.ok()) << fsl.error().message;
    EXPECT_EQ(fsl->entries.at(3).name, "Left Thalamus");
    EXPECT_DOUBLE_EQ(fsl->entries.at(3).color->y, 0.5);
    auto fs = parse_label_table("17\tLeft-Hippocampus\t220 216 20 0\n0 Unknown 0 0 0 0\n", "FreeSurferColorLUT.txt");
    ASSERT_TRUE(fs.ok()) << fs.error().message;
    EXPECT_EQ(fs->entries.at(17).name, "Left-Hippocampus");
    EXPECT_NEAR(fs->entries.at(17).color->x, 220.0 / 255.0, 1e-12);
}

TEST(LabelTable, BinaryMricronLut) {
    std::string bytes(768, '\0');
    bytes[5] = static_cast<char>(255);        // red of label 5
    bytes[256 + 5] = static_cast<char>(128);  // green
    auto t = parse_label_table(bytes, "aal.nii.lut");
    ASSERT_TRUE(t.ok()) << t.error().message;
    EXPECT_DOUBLE_EQ(t->entries.at(5).color->x, 1.0);
    EXPECT_NEAR(t->entries.at(5).color->y, 128.0 / 255.0, 1e-12);
    EXPECT_TRUE(t->entries.at(5).name.empty());
}

TEST(LabelTable, ErrorsNameTheLineAndReason) {
    auto dup = parse_label_table("1 a\n1 b\n", "t.txt");
    ASSERT_FALSE(dup.ok());
    EXPECT_NE(dup.error().message.find("t.txt:2"), std::string::npos);
    EXPECT_NE(dup.error().message.find("duplicate"), std::string::npos);
    auto bad = parse_label_table("one two\n", "t.txt");
    ASSERT_FALSE(bad.ok());
    EXPECT_NE(bad.error().message.find("not an integer"), std::string::npos);
    EXPECT_FALSE(parse_label_table("-3 x\n", "t.txt").ok());
    EXPECT_FALSE(parse_label_table("3\n", "t.txt").ok());
    EXPECT_FALSE(parse_label_table("\n# nothing\n", "t.txt").ok());
    EXPECT_FALSE(parse_label_table("4 2.0 0.5 0.5 name\n", "t.txt").ok());  // colour outside [0, 1]
}

// ---------------------------------------------------------------- NIfTI label volumes

struct Grid {
    test::VolumeSpec spec;
    std::vector<int16_t> data;
    Grid(int nx, int ny, int nz) : data(static_cast<size_t>(nx) * ny * nz, 0) {
        spec.nx = nx, spec.ny = ny, spec.nz = nz;
    }
    int16_t& at(int x, int y, int z) { return data[(static_cast<size_t>(z) * spec.ny + y) * spec.nx + x]; }
    size_t count(int16_t label, int z) {
        size_t n = 0;
        for (int y = 0; y < spec.ny; ++y)
            for (int x = 0; x < spec.nx; ++x) n += at(x, y, z) == label;
        return n;
    }
    template <typename F>
    void fill(int16_t label, F inside) {
        for (int z = 0; z < spec.nz; ++z)
            for (int y = 0; y < spec.ny; ++y)
                for (int x = 0; x < spec.nx; ++x)
                    if (inside(x, y, z)) at(x, y, z) = label;
    }
    std::string write(const std::string& name) {
        const std::string path = test::temp_path(name);
        test::write_nifti(path, spec, data, DT_INT16);
        return path;
    }
};

std::vector<const Contour*> contours_of(const Slice& s, const std::string& id) {
    std::vector<const Contour*> out;
    for (const Contour& c : s.contours)
        if (c.structure == id) out.push_back(&c);
    return out;
}

std::vector<std::vector<Vec2>> rings_of(const Slice& s, const std::string& id) {
    std::vector<std::vector<Vec2>> out;
    for (const Contour* c : contours_of(s, id)) out.push_back(c->points);
    return out;
}

TEST(NiftiImport, SphereFollowsTheSformAndVoxelAreas) {
    Grid g(24, 22, 20);
    g.spec.spacing[0] = 0.8, g.spec.spacing[1] = 1.25, g.spec.spacing[2] = 2.0;
    g.spec.origin[0] = -10.0, g.spec.origin[1] = 40.0, g.spec.origin[2] = -7.0;
    // A sphere of radius 8 mm around voxel (12, 11, 10)... in mm, anisotropic in voxels.
    g.fill(5, [&](int x, int y, int z) { return std::hypot((x - 12) * 0.8, (y - 11) * 1.25, (z - 10) * 2.0) <= 8.0; });
    const std::string path = g.write("sphere.nii.gz");
    for (double tolerance : {0.0, 0.5}) {
        ImportOptions o;
        o.tolerance = tolerance;
        auto stack = import_nifti_labels(path, o);
        ASSERT_TRUE(stack.ok()) << stack.error().message;
        ASSERT_EQ(stack->structures.size(), 1u);
        EXPECT_EQ(stack->structures[0].id, "label_5");
        size_t voxels = 0;
        double total_area = 0.0;
        for (const Slice& s : stack->slices) {
            const int k = static_cast<int>(std::lround((s.z + 7.0) / 2.0));
            ASSERT_NEAR(s.z, -7.0 + 2.0 * k, 1e-9);
            ASSERT_EQ(s.contours.size(), 1u) << "slice " << k;
            const double a = area(s.contours[0].points);
            const size_t n = g.count(5, k);
            voxels += n;
            total_area += a;
            const double pixel = 0.8 * 1.25;
            if (tolerance == 0.0) {
                EXPECT_NEAR(a, (static_cast<double>(n) - 0.5) * pixel, 1e-5 * n) << "slice " << k;  // float sform
            } else if (n > 40) {
                EXPECT_NEAR(a, n * pixel, 0.05 * n * pixel) << "slice " << k;
            }
            for (const Vec2& p : s.contours[0].points) {  // scanner mm: inside the voxel grid's extent
                EXPECT_GE(p.x, -10.0 - 0.4);
                EXPECT_LE(p.y, 40.0 + 21 * 1.25 + 0.7);
            }
        }
        const double pixel = 0.8 * 1.25;
        EXPECT_NEAR(total_area, voxels * pixel, 0.02 * voxels * pixel);
    }
}

TEST(NiftiImport, HollowSphereHasNestedHoles) {
    Grid g(21, 21, 21);
    g.fill(1, [](int x, int y, int z) {
        const double r = std::hypot(x - 10, y - 10, z - 10);
        return r <= 9.0 && r > 4.5;
    });
    auto stack = import_nifti_labels(g.write("hollow.nii"), {});
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    size_t with_hole = 0;
    for (const Slice& s : stack->slices) {
        auto rings = rings_of(s, "label_1");
        EXPECT_TRUE(rings_are_simple(rings));
        const int k = static_cast<int>(std::lround(s.z));
        if (std::abs(k - 10) <= 3) {
            ASSERT_EQ(rings.size(), 2u) << "slice " << k;
            std::sort(rings.begin(), rings.end(), [](auto& a, auto& b) { return area(a) > area(b); });
            EXPECT_GT(area(rings[0]), 0.0);
            EXPECT_LT(area(rings[1]), 0.0);  // the hole runs the other way
            // Every vertex of the hole lies inside the outer ring.
            for (const Vec2& p : rings[1]) {
                bool in = false;
                const auto& r = rings[0];
                for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
                    if ((r[i].y > p.y) != (r[j].y > p.y) &&
                        p.x < r[j].x + (p.y - r[j].y) * (r[i].x - r[j].x) / (r[i].y - r[j].y)) {
                        in = !in;
                    }
                }
                EXPECT_TRUE(in);
            }
            const double expected = static_cast<double>(g.count(1, k));
            EXPECT_NEAR(area(rings[0]) + area(rings[1]), expected, 0.06 * expected);
            ++with_hole;
        }
    }
    EXPECT_EQ(with_hole, 7u);
}

TEST(NiftiImport, TwoTouchingLabelsAndATableNameAndColourThem) {
    Grid g(20, 20, 6);
    g.fill(3, [](int x, int y, int) { return std::hypot(x - 9.5, y - 9.5) <= 7.0 && x < 10; });
    g.fill(7, [](int x, int y, int) { return std::hypot(x - 9.5, y - 9.5) <= 7.0 && x >= 10; });
    // Diagonal-only contact between the labels as well: a checkerboard patch.
    for (int z = 0; z < 6; ++z)
        for (int y = 0; y < 4; ++y)
            for (int x = 0; x < 4; ++x) g.at(x, y, z) = (x + y) % 2 ? 3 : 7;
    const std::string path = g.write("touching.nii.gz");
    const std::string table = test::temp_path("touching.txt");
    std::ofstream(table) << "3 Left half 255 0 0\n7 Right half 0 0 255\n";
    ImportOptions o;
    o.labels_path = table;
    o.jobs = 2;
    auto stack = import_nifti_labels(path, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->structures.size(), 2u);
    EXPECT_EQ(stack->structures[0].name, "Left half");
    EXPECT_EQ(stack->structures[0].id, "Left_half");
    EXPECT_DOUBLE_EQ(stack->structures[0].color.x, 1.0);
    EXPECT_EQ(stack->structures[1].name, "Right half");
    ASSERT_EQ(stack->slices.size(), 6u);
    for (const Slice& s : stack->slices) {
        auto left = rings_of(s, "Left_half"), right = rings_of(s, "Right_half");
        EXPECT_EQ(left.size(), 1u + 8u);  // the half disc + 8 checkerboard diamonds
        EXPECT_EQ(right.size(), 1u + 8u);
        EXPECT_TRUE(rings_are_simple(left));
        EXPECT_TRUE(rings_are_simple(right));
    }
    // Same result on one thread.
    o.jobs = 1;
    auto serial = import_nifti_labels(path, o);
    ASSERT_TRUE(serial.ok());
    EXPECT_EQ(contour_stack_to_json(*serial), contour_stack_to_json(*stack));
}

TEST(NiftiImport, BranchingLabelSplitsIntoTwoContours) {
    Grid g(24, 12, 12);
    g.fill(2, [](int x, int y, int z) {
        if (z < 5) return std::hypot(x - 11.5, y - 5.5) <= 5.0;                              // trunk
        return std::hypot(x - 6.0, y - 5.5) <= 3.5 || std::hypot(x - 17.0, y - 5.5) <= 3.5;  // two arms
    });
    auto stack = import_nifti_labels(g.write("branch.nii"), {});
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), 12u);
    for (const Slice& s : stack->slices) EXPECT_EQ(s.contours.size(), s.z < 4.5 ? 1u : 2u) << "z " << s.z;
}

TEST(NiftiImport, AxisStepAndOnlyOptions) {
    Grid g(10, 12, 14);
    g.fill(1, [](int x, int y, int z) { return x >= 2 && x < 8 && y >= 3 && y < 9 && z >= 1 && z < 13; });
    g.fill(2, [](int x, int, int z) { return x == 9 && z < 3; });
    const std::string path = g.write("box.nii");
    ImportOptions o;
    o.axis = 0;  // slices along x: stack (x, y, z) = scanner (y, z, x)
    o.step = 2;
    o.only = {1};
    auto stack = import_nifti_labels(path, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->structures.size(), 1u);
    ASSERT_EQ(stack->slices.size(), 3u);  // x = 2, 4, 6
    EXPECT_DOUBLE_EQ(stack->slices[0].z, 2.0);
    EXPECT_DOUBLE_EQ(stack->slices[2].z, 6.0);
    Aabb box;
    for (const Vec2& p : stack->slices[0].contours[0].points) box.extend(Vec3(p, 0.0));
    EXPECT_DOUBLE_EQ(box.min.x, 2.5);  // scanner y from 3 - 0.5
    EXPECT_DOUBLE_EQ(box.max.x, 8.5);
    EXPECT_DOUBLE_EQ(box.min.y, 0.5);  // scanner z from 1 - 0.5
    EXPECT_DOUBLE_EQ(box.max.y, 12.5);
    o.only = {4};
    auto missing = import_nifti_labels(path, o);
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().message.find("label 4"), std::string::npos);
}

TEST(NiftiImport, MinAreaDropsSpeckleAndFillsPinholes) {
    Grid g(16, 16, 3);
    g.fill(1, [](int x, int y, int) { return x >= 2 && x < 10 && y >= 2 && y < 10 && !(x == 5 && y == 5); });
    g.fill(1, [](int x, int y, int) { return x == 13 && y == 13; });  // a one-voxel island
    const std::string path = g.write("speckle.nii");
    auto all = import_nifti_labels(path, {});
    ASSERT_TRUE(all.ok()) << all.error().message;
    EXPECT_EQ(all->slices[0].contours.size(), 3u);  // block, pinhole, island
    ImportOptions o;
    o.min_area = 3.0;
    auto clean = import_nifti_labels(path, o);
    ASSERT_TRUE(clean.ok()) << clean.error().message;
    ASSERT_EQ(clean->slices[0].contours.size(), 1u);
    EXPECT_NEAR(area(clean->slices[0].contours[0].points), 64.0 - 0.5, 1e-9);
    o.min_area = 9.0;
    EXPECT_FALSE(import_nifti_labels(path, o).ok());
}

// ---------------------------------------------------------------- malformed inputs

TEST(NiftiImport, MalformedInputsAreBadInputWithAReason) {
    Grid g(16, 16, 16);
    g.fill(1, [](int x, int y, int z) { return std::hypot(x - 8, y - 8, z - 8) < 6; });
    const std::string good = g.write("good.nii.gz");
    auto bytes = read_file(good);
    ASSERT_TRUE(bytes.ok());
    const std::string truncated = test::temp_path("truncated.nii.gz");
    std::ofstream(truncated, std::ios::binary).write(bytes->data(), static_cast<std::streamsize>(bytes->size() / 2));
    auto r = import_nifti_labels(truncated, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
    EXPECT_NE(r.error().message.find("truncated"), std::string::npos) << r.error().message;

    test::VolumeSpec four = g.spec;
    four.dim4 = 3;
    const std::string fourd = test::temp_path("fourd.nii");
    test::write_nifti(fourd, four, g.data, DT_INT16);
    r = import_nifti_labels(fourd, {});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("wrong dims"), std::string::npos) << r.error().message;

    const std::string garbage = test::temp_path("garbage.nii");
    std::ofstream(garbage) << "this is not a NIfTI header";
    r = import_nifti_labels(garbage, {});
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().exit_code, kExitBadInput);

    std::vector<float> real(g.data.begin(), g.data.end());
    for (float& v : real) v *= 0.75f;
    const std::string floats = test::temp_path("prob.nii");
    test::write_nifti(floats, g.spec, real, DT_FLOAT32);
    r = import_nifti_labels(floats, {});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("--threshold"), std::string::npos) << r.error().message;
    ImportOptions o;
    o.threshold = 0.5;
    auto masked = import_nifti_labels(floats, o);
    ASSERT_TRUE(masked.ok()) << masked.error().message;
    EXPECT_EQ(masked->structures.at(0).id, "mask");

    auto empty = import_nifti_labels(Grid(4, 4, 4).write("empty.nii"), {});
    EXPECT_FALSE(empty.ok());
}

// ---------------------------------------------------------------- RT-STRUCT

const char* kRtStruct = "/usr/lib/python3/dist-packages/pydicom/data/test_files/rtstruct.dcm";

TEST(RtStructImport, PydicomSampleHasTheRightRoisAndContours) {
    if (!std::filesystem::exists(kRtStruct)) GTEST_SKIP() << "needs Debian package python3-pydicom";
    std::vector<std::string> notes;
    ImportOptions o;
    o.note = [&](const std::string& m) { notes.push_back(m); };
    auto stack = load_any_contour_source(kRtStruct, o);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    // Expected values read independently with pydicom: ROIs 1 'patient' (3 CLOSED_PLANAR contours at
    // z = -200, -190, -180 with 5, 6, 6 points, colour 220\160\120), 2 'Isocenter 1' and 3 'Isocenter 2'
    // (one POINT contour each).
    ASSERT_EQ(stack->structures.size(), 1u);
    EXPECT_EQ(stack->structures[0].name, "patient");
    EXPECT_NEAR(stack->structures[0].color.x, 220.0 / 255.0, 1e-12);
    EXPECT_NEAR(stack->structures[0].color.y, 160.0 / 255.0, 1e-12);
    EXPECT_NEAR(stack->structures[0].color.z, 120.0 / 255.0, 1e-12);
    ASSERT_EQ(stack->slices.size(), 3u);
    const double z[3] = {-200.0, -190.0, -180.0};
    const size_t points[3] = {4, 5, 5};  // 5, 6, 6 stored; each repeats its first point at the end
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_DOUBLE_EQ(stack->slices[i].z, z[i]);
        ASSERT_EQ(stack->slices[i].contours.size(), 1u);
        EXPECT_EQ(stack->slices[i].contours[0].points.size(), points[i]);
    }
    size_t skipped = 0;
    for (const auto& n : notes) skipped += n.find("POINT") != std::string::npos;
    EXPECT_EQ(skipped, 2u);
    // The stack round-trips through the file format.
    auto parsed = parse_contour_stack(contour_stack_to_json(*stack), "rt.json");
    EXPECT_TRUE(parsed.ok()) << parsed.error().message;
}

// A header niftilib would "repair" or read anyway is refused at its byte.
TEST(NiftiImport, HeaderFieldsOutsideTheFormatAreRefusedAtTheirByte) {
    Grid g(8, 8, 8);
    g.fill(1, [](int x, int y, int z) { return x > 2 && y > 2 && z > 2; });
    const std::string good = g.write("hdr_good.nii");
    auto bytes = read_file(good);
    ASSERT_TRUE(bytes.ok());
    struct Case {
        const char* name;
        size_t at;
        std::vector<uint8_t> patch;
        const char* expect;
    };
    const Case cases[] = {
        {"negative_dim.nii", 42, {0xfe, 0xff}, "header byte 42: wrong dims: dim[1] = -2"},
        {"zero_dim.nii", 44, {0, 0}, "header byte 44: wrong dims: dim[2] = 0"},
        {"magic.nii", 344, {'x', 'y', 'z', 0}, "header byte 344: magic is 'xyz\\x00'"},
        {"sizeof_hdr.nii", 0, {0, 0, 0, 0}, "header byte 0: sizeof_hdr is 0, not 348"},
    };
    for (const Case& c : cases) {
        std::string b = *bytes;
        for (size_t k = 0; k < c.patch.size(); ++k) b[c.at + k] = char(c.patch[k]);
        const std::string path = test::temp_path(c.name);
        std::ofstream(path, std::ios::binary).write(b.data(), std::streamsize(b.size()));
        auto r = import_nifti_labels(path, {});
        ASSERT_FALSE(r.ok()) << c.name;
        EXPECT_EQ(r.error().exit_code, kExitBadInput);
        EXPECT_EQ(r.error().message.rfind(path + ": " + c.expect, 0), 0u) << r.error().message;
    }
}

}  // namespace
}  // namespace body
