// Label volume -> contours -> meshes: the synthetic shapes of import_test.cpp
// through the reconstruction pipeline.
//
// Volume convention (see builder/import/import.h): in-plane the surface lies on
// the voxel faces (marching squares, half-voxel vertices); along the slice axis
// the mesh runs from the plane through the voxel centres of the first slice to
// that of the last, closed by flat caps there. So the reference volume of a
// label is its voxel volume less half of the voxels of its first and last
// slice (the trapezoidal rule over the slices). Meshes must be within 2% of it;
// round shapes, whose end slices are small, also within 2% of the plain voxel
// volume.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <optional>
#include <set>

#include "builder/import/import.h"
#include "builder/pipeline/build_pipeline.h"
#include "shared/mesh.h"
#include "tests/import/nifti_test_util.h"

namespace body {
namespace {

[[maybe_unused]] ::testing::Environment* const kCleanup = ::testing::AddGlobalTestEnvironment(new test::TempCleanup);

struct Shape {
    const char* name;
    int n;
    double spacing[3];
    bool (*inside)(double x, double y, double z);  // voxel-centre coordinates relative to the grid centre, in mm
};

// Builds the shape and checks topology and volume.
// The label volume written as a NIfTI file, read back as a contour stack and
// built with the default options.
template <typename T>
Result<std::vector<StructureMesh>> build_label_volume(const std::string& name, const test::VolumeSpec& spec,
                                                      const std::vector<T>& data, int datatype) {
    const std::string path = test::temp_path(name + ".nii.gz");
    test::write_nifti(path, spec, data, datatype);
    auto stack = load_any_contour_source(path, {});
    std::filesystem::remove(path);
    if (!stack) return stack.error();
    return build_structures(*stack, {}, path);
}

void build_and_compare(const Shape& shape, size_t expected_components, long expected_genus, bool plain_too) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = shape.n;
    for (int i = 0; i < 3; ++i) spec.spacing[i] = shape.spacing[i], spec.origin[i] = 3.0 * i;
    std::vector<int16_t> data(static_cast<size_t>(shape.n) * shape.n * shape.n, 0);
    size_t voxels = 0;
    const double c = (shape.n - 1) / 2.0;
    auto in = [&](int x, int y, int z) {
        if (z < 0 || z >= shape.n) return false;
        return shape.inside((x - c) * spec.spacing[0], (y - c) * spec.spacing[1], (z - c) * spec.spacing[2]);
    };
    std::vector<size_t> per_slice;
    for (int z = 0; z < shape.n; ++z) {
        size_t n = 0;
        for (int y = 0; y < shape.n; ++y)
            for (int x = 0; x < shape.n; ++x)
                if (in(x, y, z)) {
                    data[(static_cast<size_t>(z) * shape.n + y) * shape.n + x] = 9;
                    ++n;
                }
        if (n > 0) per_slice.push_back(n);
        voxels += n;
    }
    ASSERT_GE(per_slice.size(), 2u);
    const double convention_voxels =
        static_cast<double>(voxels) - 0.5 * static_cast<double>(per_slice.front() + per_slice.back());
    auto built = build_label_volume(shape.name, spec, data, DT_INT16);
    ASSERT_TRUE(built.ok()) << built.error().message;
    ASSERT_EQ(built->size(), 1u);
    const StructureMesh& m = built->front();
    EXPECT_TRUE(m.closed_manifold) << shape.name;
    EXPECT_EQ(m.components, expected_components) << shape.name;
    EXPECT_EQ(m.genus, expected_genus) << shape.name;
    const double voxel = spec.spacing[0] * spec.spacing[1] * spec.spacing[2];
    const double convention_volume = convention_voxels * voxel;
    EXPECT_NEAR(m.volume, convention_volume, 0.02 * convention_volume)
        << shape.name << ": mesh " << m.volume << " mm^3, " << voxels << " voxels";
    if (plain_too) {
        const double voxel_volume = static_cast<double>(voxels) * voxel;
        EXPECT_NEAR(m.volume, voxel_volume, 0.02 * voxel_volume) << shape.name << ": mesh " << m.volume << " mm^3";
    }
}

TEST(ImportBuild, SphereVolumeMatchesItsVoxels) {
    build_and_compare({"sphere",
                       26,
                       {1.0, 1.0, 1.0},
                       [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z) <= 10.0; }},
                      1, 0, true);
}

TEST(ImportBuild, AnisotropicEllipsoidVolumeMatchesItsVoxels) {
    build_and_compare({"ellipsoid",
                       26,
                       {0.9, 1.1, 1.5},
                       [](double x, double y, double z) { return std::hypot(x / 10.0, y / 8.0, z / 15.0) <= 1.0; }},
                      1, 0, true);
}

TEST(ImportBuild, HollowSphereKeepsItsCavity) {
    // One closed surface outside, one (inward-facing) around the cavity.
    build_and_compare({"hollow",
                       26,
                       {1.0, 1.0, 1.0},
                       [](double x, double y, double z) {
                           const double r = std::sqrt(x * x + y * y + z * z);
                           return r <= 11.0 && r > 6.0;
                       }},
                      2, 0, true);
}

TEST(ImportBuild, BranchingLabelIsOneClosedSolid) {
    // A trunk splitting into two arms (a "Y" along z).
    build_and_compare({"branch",
                       28,
                       {1.0, 1.0, 1.0},
                       [](double x, double y, double z) {
                           if (z < -12.0 || z > 12.0) return false;
                           if (z < 0.0) return std::hypot(x, y) <= 8.0;
                           return std::hypot(x - 6.0, y) <= 4.5 || std::hypot(x + 6.0, y) <= 4.5;
                       }},
                      1, 0, false);
}

// Speckle next to small regions, with the default options (no --min-area): a
// 5x5 block (8 contour vertices) between two layers of nine one-voxel islands,
// a voxel over four islands, a voxel over two. Partition branching gets fewer
// contour vertices than its branches need and must add its own; tiny regions
// are never an error.
TEST(ImportBuild, SpeckleOverTinyRegionsBuildsClosed) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 12;
    std::vector<uint8_t> data(12 * 12 * 12, 0);
    auto set = [&](int x, int y, int z) { data[(static_cast<size_t>(z) * 12 + y) * 12 + x] = 4; };
    auto islands = [&](int z) {
        for (int y : {3, 5, 7})
            for (int x : {3, 5, 7}) set(x, y, z);
    };
    islands(2);
    for (int y = 3; y <= 7; ++y)
        for (int x = 3; x <= 7; ++x) set(x, y, 3);
    islands(4);
    set(5, 5, 5);
    for (int y : {4, 6})
        for (int x : {4, 6}) set(x, y, 6);
    set(5, 5, 7);
    set(4, 5, 8), set(6, 5, 8);
    auto built = build_label_volume("speckle", spec, data, DT_UINT8);
    ASSERT_TRUE(built.ok()) << built.error().message;
    ASSERT_EQ(built->size(), 1u);
    const StructureMesh& m = built->front();
    const MeshTopology t = analyze_topology(m.mesh.positions, m.mesh.indices);
    EXPECT_TRUE(t.closed_manifold()) << t.boundary_edges << " boundary, " << t.nonmanifold_edges << " non-manifold, "
                                     << t.misoriented_edges << " misoriented edges, " << t.nonmanifold_vertices
                                     << " non-manifold vertices, " << t.degenerate_triangles << " degenerate triangles";
    EXPECT_GT(m.volume, 0.0);
    EXPECT_LT(m.volume, 52.0);  // 50 voxels of 1 mm^3
}

// A thin label (a slab 2 voxels thick inside another label) with a lobe
// hanging over it by a neck one voxel wide and two high: one 6-connected
// piece. Its narrow blur keeps the neck only as a speck under the slab's
// rings, so the lobe's rings were joined to the slab through the speck and
// left as a piece of their own once specks were dropped. The label must come
// out as one closed solid that keeps the slab (a 2-slice slab's mesh spans
// one slice gap plus its domes: about 3/4 of its voxels).
TEST(ImportBuild, ThinLabelWithANeckIsOneSolid) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 40;
    std::vector<int16_t> data(size_t(40) * 40 * 40, 0);
    size_t slab = 0;
    for (int z = 3; z < 37; ++z)
        for (int y = 3; y < 37; ++y)
            for (int x = 3; x < 37; ++x) {
                int16_t l = 2;
                if (z >= 19 && z <= 20 && x >= 6 && x <= 30 && y >= 6 && y <= 30) l = 1, ++slab;
                if (x == 18 && y == 18 && (z == 21 || z == 22)) l = 1;                        // the neck
                if (x >= 17 && x <= 19 && y >= 17 && y <= 19 && (z == 23 || z == 24)) l = 1;  // the lobe
                data[(size_t(z) * 40 + size_t(y)) * 40 + size_t(x)] = l;
            }
    const std::string path = test::temp_path("neck.nii.gz");
    test::write_nifti(path, spec, data, DT_INT16);
    ImportOptions o;
    o.label_smooth = 2.0;  // the CLI's default
    auto stack = import_nifti_labels(path, o);
    std::filesystem::remove(path);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    auto built = build_structures(*stack, {}, path);
    ASSERT_TRUE(built.ok()) << built.error().message;
    ASSERT_EQ(built->size(), 2u);
    const StructureMesh& m = built->front();
    ASSERT_EQ(m.id, "label_1");
    EXPECT_TRUE(m.closed_manifold);
    EXPECT_EQ(m.components, 1u);
    EXPECT_GT(m.volume, 0.6 * double(slab));
    EXPECT_LT(m.volume, double(slab));
}

// The rings between slices scale with the voxel (BuildOptions::ring_voxel;
// 0.25 is the command line's default): a 1 mm sphere sliced at every voxel,
// its gap the voxel itself, keeps under a quarter of the ring points the gap
// rule alone gives it (1 mm gaps: 0.004 mm); sliced at every 4th voxel it
// keeps a larger share.
TEST(ImportBuild, RingVoxelScalesTheRingsWithTheVoxel) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 30;
    std::vector<int16_t> data(30 * 30 * 30, 0);
    for (int z = 0; z < 30; ++z)
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 30; ++x)
                if (std::hypot(x - 14.5, y - 14.5, z - 14.5) <= 12.0) data[(size_t(z) * 30 + size_t(y)) * 30 + x] = 3;
    const std::string path = test::temp_path("rings.nii.gz");
    test::write_nifti(path, spec, data, DT_INT16);
    // Vertices strictly between two slices of the stack: the ring points.
    auto ring_points = [&](int step, double ring_voxel) -> size_t {
        ImportOptions import;
        import.step = step;
        auto stack = load_any_contour_source(path, import);
        EXPECT_TRUE(stack.ok());
        if (!stack.ok()) return 0;
        EXPECT_EQ(stack->voxel, std::optional<double>(1.0));
        BuildOptions options;
        options.interpolate = 3;
        options.ring_voxel = ring_voxel;
        auto built = build_structures(*stack, options, path);
        EXPECT_TRUE(built.ok() && built->size() == 1);
        if (!built.ok() || built->size() != 1) return 0;
        EXPECT_TRUE(built->front().closed_manifold);
        std::set<double> slices;
        for (const Slice& sl : stack->slices) slices.insert(sl.z);
        size_t n = 0;
        for (const Vec3& p : built->front().mesh.positions)
            n += p.z > *slices.begin() && p.z < *slices.rbegin() && !slices.count(p.z);
        return n;
    };
    const size_t dense_gap_rule = ring_points(1, 0.0), dense = ring_points(1, 0.25);
    const size_t sparse_gap_rule = ring_points(4, 0.0), sparse = ring_points(4, 0.25);
    RecordProperty("dense", std::to_string(dense) + " of " + std::to_string(dense_gap_rule));
    RecordProperty("sparse", std::to_string(sparse) + " of " + std::to_string(sparse_gap_rule));
    EXPECT_GT(dense_gap_rule, 500u);
    EXPECT_LT(dense * 4, dense_gap_rule);  // the gap rule alone: every one
    EXPECT_GT(sparse, 0u);
    // The sparse stack keeps a larger share: its linear bands leave the sphere
    // by more than a quarter voxel (about gap^2 / 8R = 0.17 mm at the equator
    // for 4 mm gaps, against 0.01 mm for 1 mm ones).
    EXPECT_GT(sparse * dense_gap_rule, dense * sparse_gap_rule);
}

}  // namespace
}  // namespace body
