// `bodygen exhibit` end to end: label volumes stored in different array layouts
// end up the same way round, colour tables and RT-STRUCT colours reach the
// scene, a failing structure is left out (or fails the run with --strict), mesh
// directories become models, and `lod`/`pack` honour --quiet and --json.
#include <gtest/gtest.h>
#include <nifti1_io.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "builder/exhibit/exhibit.h"
#include "builder/exhibit/slices_volume.h"
#include "builder/import/grey_volume.h"
#include "builder/import/import.h"
#include "tests/cli/cli_test.h"
#include "tests/import/nifti_test_util.h"

namespace body {
namespace {

namespace fs = std::filesystem;

[[maybe_unused]] ::testing::Environment* const kCleanup = ::testing::AddGlobalTestEnvironment(new test::TempCleanup);

std::string bodygen() { return test::bin("bodygen"); }

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

nlohmann::json read_json(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in, nullptr, false);
}

// A block of label 1 at voxels i in [2,5], j in [2,9], k in [2,15] of a 12x12x20
// grid, written with the voxel -> RAS matrix `m` (rows x, y, z; columns i, j, k, t).
// `layout` permutes/mirrors how the same voxels sit in the array.
std::string write_block(const std::string& name, const float m[3][4], bool mirror_i) {
    const int nx = 12, ny = 12, nz = 20;
    std::vector<uint8_t> data(size_t(nx * ny * nz), 0);
    for (int k = 2; k <= 15; ++k)
        for (int j = 2; j <= 9; ++j)
            for (int i = 2; i <= 5; ++i) data[size_t((k * ny + j) * nx + (mirror_i ? nx - 1 - i : i))] = 1;
    const int dims[8] = {3, nx, ny, nz, 1, 1, 1, 1};
    nifti_image* nim = nifti_make_new_nim(dims, DT_UINT8, 1);
    std::memcpy(nim->data, data.data(), data.size());
    nim->qform_code = 0;
    nim->sform_code = 1;
    std::memset(&nim->sto_xyz, 0, sizeof nim->sto_xyz);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) nim->sto_xyz.m[r][c] = m[r][c];
    nim->sto_xyz.m[3][3] = 1.0f;
    const std::string path = test::temp_path(name);
    nifti_set_filenames(nim, path.c_str(), 0, 1);
    nifti_image_write(nim);
    nifti_image_free(nim);
    return path;
}

// The block's extent in the kiosk frame after the exhibit's rotation.
Vec3 kiosk_extent(const std::string& path, int axis) {
    ImportOptions o;
    o.axis = axis;
    auto stack = import_nifti_labels(path, o);
    EXPECT_TRUE(stack) << stack.error().message;
    if (!stack) return Vec3(0.0);
    const auto parts = exhibit::parts_from_stack(*stack, path, *exhibit::parse_orientation("RAS"));
    const auto built = exhibit::build_parts(parts, exhibit::PartOptions{});
    EXPECT_EQ(built.size(), 1u);
    EXPECT_FALSE(built[0].error) << built[0].error->message;
    return built[0].hi - built[0].lo;
}

// The same anatomy (4 mm left-right, 8 mm front-back, 14 mm head-foot) stored
// as RAS, with a mirrored first array axis (LAS) and with the array axes
// permuted (i = superior, j = right, k = anterior), sliced along each array
// axis: always X = left-right, Y = head-foot, Z = front-back in the kiosk.
TEST(ExhibitCli, CameraFrameFollowsThePatientNotTheArray) {
    const float ras[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const float las[3][4] = {{-1, 0, 0, 11}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    // Permuted: the block's i (4 voxels) is superior, j (8) right, k (14) anterior,
    // so here the block is 8 wide, 14 deep and 4 tall.
    const float perm[3][4] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {1, 0, 0, 0}};
    for (int axis = 0; axis < 3; ++axis) {
        SCOPED_TRACE("axis " + std::to_string(axis));
        for (const auto& [name, m, mirrored] : {std::tuple{"ras.nii", ras, false}, std::tuple{"las.nii", las, true}}) {
            const Vec3 e = kiosk_extent(write_block(name, m, mirrored), axis);
            EXPECT_NEAR(e.x, 4.0, 1.01) << name;
            EXPECT_NEAR(e.y, 14.0, 1.01) << name;
            EXPECT_NEAR(e.z, 8.0, 1.01) << name;
        }
        const Vec3 e = kiosk_extent(write_block("perm.nii", perm, false), axis);
        EXPECT_NEAR(e.x, 8.0, 1.01);
        EXPECT_NEAR(e.y, 4.0, 1.01);
        EXPECT_NEAR(e.z, 14.0, 1.01);
    }
}

// Two labels, an ITK-SNAP label description beside the volume, a group table and
// translations: the bundle's scene has their colours, titles, groups and languages.
TEST(ExhibitCli, LabelVolumeWithItkSnapColoursGroupsAndTranslations) {
    test::VolumeSpec spec;
    spec.nx = spec.ny = spec.nz = 12;
    std::vector<uint8_t> data(12 * 12 * 12, 0);
    for (int z = 2; z < 10; ++z)
        for (int y = 2; y < 10; ++y)
            for (int x = 1; x < 11; ++x) data[size_t((z * 12 + y) * 12 + x)] = x < 6 ? 1 : 2;
    const std::string volume = test::temp_path("pair.nii");
    test::write_nifti(volume, spec, data, DT_UINT8);
    const std::string labels = test::temp_path("pair_labels.txt");
    write_text(labels,
               "# ITK-SNAP Label Description File\n"
               "    0     0    0    0        0  0  0    \"Clear Label\"\n"
               "    1   255    0    0        1  1  1    \"Hippocampus_R\"\n"
               "    2     0    0  255        1  1  1    \"Hippocampus_L\"\n");
    const std::string groups = test::temp_path("groups.tsv");
    write_text(groups, "Hippo*\tlimbic-{side}\n");
    const std::string tr = test::temp_path("tr.tsv");
    write_text(tr, "Hippocampus_L\tde\tHippocampus (links)\tBildet Erinnerungen\n");
    const std::string bundle = test::temp_path("pair_bundle");
    const auto r = test::run(bodygen() + " exhibit " + volume + " --labels " + labels + " --groups " + groups +
                             " --translations " + tr + " --view left --jobs 2 -o " + bundle);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto scene = read_json(bundle + "/scene.json");
    ASSERT_EQ(scene["models"].size(), 2u) << scene.dump();
    EXPECT_EQ(scene["kiosk"]["languages"], nlohmann::json({"en", "de"}));
    EXPECT_EQ(scene["camera"]["azimuth_deg"], 90.0);
    for (const auto& m : scene["models"]) {
        ASSERT_TRUE(fs::is_regular_file(bundle + "/" + m["file"].get<std::string>()));
        if (m["name"] == "Hippocampus_R") {
            EXPECT_EQ(m["colour"], nlohmann::json({1.0, 0.0, 0.0}));
            EXPECT_EQ(m["group"], "limbic-right");
            EXPECT_EQ(m["label"]["en"]["title"], "Hippocampus (right)");
        } else {
            EXPECT_EQ(m["colour"], nlohmann::json({0.0, 0.0, 1.0}));
            EXPECT_EQ(m["group"], "limbic-left");
            EXPECT_EQ(m["label"]["de"]["title"], "Hippocampus (links)");
        }
    }
    // The bundle is what `bodygen pack` accepts as input again.
    const auto again = test::run(bodygen() + " pack " + bundle + "/scene.json -o " + bundle + "_again --quiet");
    EXPECT_EQ(again.exit_code, 0) << again.output;
    EXPECT_EQ(again.output, "");
}

TEST(ExhibitCli, FailingStructureLeftOutStrictFailsNoneBuiltIsExitOne) {
    const std::string stack = test::temp_path("two.contours.json");
    write_text(stack, R"({"format": "bodygen.contours", "version": 1, "units": "mm",
 "structures": [{"id": "good", "name": "Good_L"}, {"id": "bad", "name": "Bad", "color": [0.2, 0.4, 0.6]}],
 "slices": [{"z": 0, "contours": [{"points": [[0,0],[4,0],[4,4],[0,4]], "structure": "good"}]},
  {"z": 1, "contours": [{"points": [[0,0],[4,0],[4,4],[0,4]], "structure": "good"},
                        {"points": [[10,0],[11,0]], "structure": "bad"}]},
  {"z": 2, "contours": [{"points": [[0,0],[4,0],[4,4],[0,4]], "structure": "good"}]}]})");
    const std::string bundle = test::temp_path("two_bundle");
    auto r = test::run(bodygen() + " exhibit " + stack + " -o " + bundle);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("left out Bad: " + stack + ": slice 1 contour 1"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1 of 2 structures"), std::string::npos) << r.output;
    EXPECT_EQ(read_json(bundle + "/scene.json")["models"].size(), 1u);

    r = test::run(bodygen() + " exhibit " + stack + " --json --quiet -o " + bundle + "_json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.output;
    EXPECT_EQ(j["models"], 1);
    ASSERT_EQ(j["failed"].size(), 1u);
    EXPECT_EQ(j["failed"][0]["name"], "Bad");

    r = test::run(bodygen() + " exhibit " + stack + " --strict -o " + bundle + "_strict");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_FALSE(fs::exists(bundle + "_strict"));

    const std::string only_bad = test::temp_path("bad.contours.json");
    write_text(only_bad, R"({"format": "bodygen.contours", "version": 1, "units": "mm",
 "structures": [{"id": "bad", "name": "Bad"}],
 "slices": [{"z": 1, "contours": [{"points": [[10,0],[11,0]], "structure": "bad"}]}]})");
    r = test::run(bodygen() + " exhibit " + only_bad + " -o " + bundle + "_none");
    EXPECT_EQ(r.exit_code, 1) << r.output;
    EXPECT_FALSE(fs::exists(bundle + "_none"));
    // No stray work or staging directories beside the bundles.
    for (const auto& e : fs::directory_iterator(test::temp_dir()))
        EXPECT_EQ(e.path().filename().string().find(".work-"), std::string::npos) << e.path();
}

TEST(ExhibitCli, MeshDirectoryGetsDistinctColoursAndReadableNames) {
    const fs::path dir = test::temp_path("meshes");
    fs::create_directories(dir);
    const std::string smoke = std::string(BODY_TEST_DATA_DIR) + "/models/smoke.obj";
    fs::copy_file(smoke, dir / "Left_kidney.obj", fs::copy_options::overwrite_existing);
    fs::copy_file(smoke, dir / "Right_kidney.obj", fs::copy_options::overwrite_existing);
    const std::string bundle = test::temp_path("mesh_bundle");
    const auto r = test::run(bodygen() + " exhibit " + dir.string() + " --orientation LPS -o " + bundle);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto scene = read_json(bundle + "/scene.json");
    ASSERT_EQ(scene["models"].size(), 2u);
    EXPECT_EQ(scene["models"][0]["label"]["en"]["title"], "Kidney (left)");
    EXPECT_NE(scene["models"][0]["colour"], scene["models"][1]["colour"]);  // touching: apart
    // LPS data: Euler (-90, 0, 0) turns superior (+z) up and anterior (-y) toward the camera.
    EXPECT_EQ(scene["models"][0]["transform"]["rotate_deg"], nlohmann::json({-90.0, 0.0, 0.0}));

    const auto bad = test::run(bodygen() + " exhibit " + dir.string() + " --orientation RAR -o " + bundle + "_x");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.output.find("--orientation"), std::string::npos);
}

TEST(ExhibitCli, RtStructColoursReachTheScene) {
    const char* rt = "/usr/lib/python3/dist-packages/pydicom/data/test_files/rtstruct.dcm";
    if (!fs::exists(rt)) GTEST_SKIP() << "needs Debian python3-pydicom (its test RT-STRUCT)";
    const std::string bundle = test::temp_path("rt_bundle");
    const auto r = test::run(bodygen() + " exhibit " + rt + " --quiet --json -o " + bundle);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto scene = read_json(bundle + "/scene.json");
    ASSERT_GE(scene["models"].size(), 1u);
    auto stack = import_rtstruct(rt, ImportOptions{});
    ASSERT_TRUE(stack);
    const auto parts = exhibit::parts_from_stack(*stack, rt, *exhibit::parse_orientation("RAS"));
    const auto stems = exhibit::model_stems(parts);
    for (const auto& m : scene["models"]) {
        const size_t i = size_t(std::find(stems.begin(), stems.end(), m["name"].get<std::string>()) - stems.begin());
        ASSERT_LT(i, stems.size()) << m["name"];
        ASSERT_TRUE(parts[i].colour) << m["name"];  // every ROI of this file has a Display Color
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(m["colour"][size_t(k)].get<double>(), (*parts[i].colour)[k], 1e-3);
    }
}

TEST(ExhibitCli, LodAndPackHonourQuietAndJson) {
    const std::string smoke = std::string(BODY_TEST_DATA_DIR) + "/models/smoke.obj";
    const std::string out = test::temp_path("smoke.bpm");
    auto r = test::run(bodygen() + " lod " + smoke + " -o " + out + " --quiet");
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_EQ(r.output, "");
    r = test::run(bodygen() + " lod " + smoke + " -o " + out + " --json --jobs 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto j = nlohmann::json::parse(r.output, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.output;
    EXPECT_EQ(j["triangles"], 320);
}

}  // namespace
}  // namespace body

namespace body {
namespace {

// The grey-level volume lands where the models do: the block's voxels, read
// back as a grey image (label 1 -> 255 after the window), have their centres
// inside the block's mesh in the kiosk frame and half a voxel from its sides,
// for a RAS, a mirrored (LAS) and a permuted array, sliced along each axis.
TEST(ExhibitCli, SlicesVolumeIsPlacedAsTheModels) {
    const float ras[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const float las[3][4] = {{-1, 0, 0, 11}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const float perm[3][4] = {{0, 1, 0, 0}, {0, 0, 1, 0}, {1, 0, 0, 0}};
    for (int axis = 0; axis < 3; ++axis)
        for (const auto& [name, m, mirrored] : {std::tuple{"g_ras.nii", ras, false}, std::tuple{"g_las.nii", las, true},
                                                std::tuple{"g_perm.nii", perm, false}}) {
            SCOPED_TRACE(std::string(name) + " axis " + std::to_string(axis));
            const std::string path = write_block(name, m, mirrored);
            ImportOptions o;
            o.axis = axis;
            auto stack = import_nifti_labels(path, o);
            ASSERT_TRUE(stack) << stack.error().message;
            const auto axes = *exhibit::parse_orientation("RAS");
            const auto parts = exhibit::parts_from_stack(*stack, path, axes);
            const auto built = exhibit::build_parts(parts, exhibit::PartOptions{});
            ASSERT_FALSE(built[0].error);
            auto grey = read_grey_image(path);
            ASSERT_TRUE(grey) << grey.error().message;
            auto v = exhibit::slices_volume(grey->dim, grey->values, grey->affine,
                                            exhibit::volume_axes(parts, built, axes), path);
            ASSERT_TRUE(v) << v.error().message;
            Vec3 lo(1e9), hi(-1e9);
            size_t n = 0;
            for (uint32_t k = 0; k < v->dims[2]; ++k)
                for (uint32_t j = 0; j < v->dims[1]; ++j)
                    for (uint32_t i = 0; i < v->dims[0]; ++i) {
                        const uint8_t g = v->voxels[(size_t(k) * v->dims[1] + j) * v->dims[0] + i];
                        ASSERT_TRUE(g == 0 || g == 255) << int(g);
                        if (g == 0) continue;
                        ++n;
                        Vec3 p;
                        for (size_t r = 0; r < 3; ++r)
                            p[int(r)] = v->affine[r * 4] * i + v->affine[r * 4 + 1] * j + v->affine[r * 4 + 2] * k +
                                        v->affine[r * 4 + 3];
                        lo = glm::min(lo, p), hi = glm::max(hi, p);
                    }
            EXPECT_EQ(n, 4u * 8u * 14u);
            for (int a = 0; a < 3; ++a) {
                EXPECT_GE(lo[a], built[0].lo[a] - 0.01) << "axis " << a;
                EXPECT_LE(hi[a], built[0].hi[a] + 0.01) << "axis " << a;
                EXPECT_NEAR(lo[a] - built[0].lo[a], 0.5, 0.51) << "axis " << a;
                EXPECT_NEAR(built[0].hi[a] - hi[a], 0.5, 0.51) << "axis " << a;
            }
        }
}

// `--slices-volume`: the bundle gets slices.vol and cut_plane.volume; a bad
// image is one located line, exit 2 and no bundle.
TEST(ExhibitCli, SlicesVolumeInTheBundleAndBadImagesStop) {
    const float ras[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    const std::string volume = write_block("sv_block.nii", ras, false);
    const std::string bundle = test::temp_path("sv_bundle");
    auto r = test::run(bodygen() + " exhibit " + volume + " --slices-volume " + volume + " --quiet -o " + bundle);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(read_json(bundle + "/scene.json")["cut_plane"]["volume"], "slices.vol");
    EXPECT_EQ(fs::file_size(bundle + "/slices.vol"), 68u + 12u * 12u * 20u);
    const std::string text = test::temp_path("sv_not.nii");
    write_text(text, "not a nifti image at all");
    const std::string bad_bundle = test::temp_path("sv_bad");
    r = test::run(bodygen() + " exhibit " + volume + " --slices-volume " + text + " --quiet -o " + bad_bundle);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(text), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(bad_bundle));
}

}  // namespace
}  // namespace body
