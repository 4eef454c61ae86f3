// Progressive meshes on the Stanford bunny (Debian glmark2-data) and the bodygen
// lod/extract/info commands end to end. Label cli: the bunny build is too slow
// for the qemu-aarch64 unit run.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/cli/cli_test.h"
#include "tests/lod/level_checks.h"

namespace body {
namespace {

constexpr const char* kBunny = "/usr/share/glmark2/models/bunny.obj";

class LodBunny : public ::testing::Test {
protected:
    void SetUp() override {
        if (!std::filesystem::exists(kBunny)) GTEST_SKIP() << "needs " << kBunny << " (Debian package glmark2-data)";
        auto m = read_obj_merged(kBunny);
        ASSERT_TRUE(m.ok()) << m.error().message;
        bunny_ = std::move(*m);
    }
    Mesh bunny_;
};

TEST_F(LodBunny, EveryLevelIsAClosedManifoldWithinItsStoredError) {
    const MeshTopology input = analyze_topology(bunny_.positions, bunny_.indices);
    ASSERT_TRUE(input.closed_manifold()) << "the packaged bunny is expected to be closed";
    auto bytes = lod::encode_bpm(std::vector<Mesh>{bunny_});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    auto pms = pm::read_bpm_bytes(*bytes, "bunny.bpm");
    ASSERT_TRUE(pms.ok()) << pms.error().message;
    pm::ProgressiveMesh& m = *(*pms)[0];
    EXPECT_EQ(m.max_triangle_count(), bunny_.triangle_count());
    EXPECT_LE(m.base_triangle_count(), bunny_.triangle_count() / 100);
    std::printf("bunny: %zu bytes, %zu splits, %.2f bytes/split, base %zu triangles\n", bytes->size(), m.max_level(),
                double(bytes->size()) / double(m.max_level()), m.base_triangle_count());
    // (The scan itself has a few back-to-back neighbours: no level may be worse.)
    const test::SampledLevels checked = test::expect_sampled_levels_within_stored_error(m, bunny_);
    std::printf("bunny: worst measured/stored Hausdorff %.3f\n", checked.worst_ratio);
    EXPECT_GE(checked.levels, 20);
}

// The bunny's .bpm bytes are pinned: speed work on the simplifier or the writer must
// not change a collapse, a placement or a byte (the accuracy figures were measured on
// these bytes, with little margin). The icosphere golden (test_lod) checks platforms;
// this one checks a real mesh's collapse order.
TEST_F(LodBunny, BytesArePinned) {
    auto bytes = lod::encode_bpm(std::vector<Mesh>{bunny_});
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    const uint32_t crc = pm::crc32(*bytes);
    EXPECT_EQ(crc, BODY_LOD_BUNNY_GOLDEN_CRC)
        << "the bunny's .bpm changed (" << bytes->size() << " bytes, crc32 " << std::hex << crc
        << "): if intended, re-measure the accuracy (bench_pm) and update BODY_LOD_BUNNY_GOLDEN_CRC";
}

TEST_F(LodBunny, CommandsRoundTrip) {
    const std::string dir = std::string(BODY_BINARY_DIR) + "/tests/lod";
    const std::string bpm = dir + "/bunny_cli.bpm", obj = dir + "/bunny_cli_10.obj";
    auto r = test::run(test::bin("bodygen") + " lod " + kBunny + " -o " + bpm + " --min-triangles 500 --sizes");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("SPLT bytes per split"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("parent number"), std::string::npos) << r.output;
    r = test::run(test::bin("bodygen") + " info " + bpm);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("69666 triangles"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("bytes per split; full mesh, 16-bit positions, 8-bit normals: meshoptimizer codecs"),
              std::string::npos)
        << r.output;
    r = test::run(test::bin("bodygen") + " extract " + bpm + " --ratio 0.1 -o " + obj);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto level = read_obj_merged(obj);
    ASSERT_TRUE(level.ok()) << level.error().message;
    EXPECT_LE(level->triangle_count(), 6967u);
    EXPECT_GE(level->triangle_count(), 6900u);
    EXPECT_TRUE(analyze_topology(level->positions, level->indices).closed_manifold());
    r = test::run(test::bin("bodygen") + " extract " + bpm + " --triangles 10 -o " + obj);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto base = read_obj_merged(obj);
    ASSERT_TRUE(base.ok());
    EXPECT_GE(base->triangle_count(), 500u);  // --min-triangles kept
    // Bad usage and bad files exit 2 with a message.
    r = test::run(test::bin("bodygen") + " extract " + bpm + " -o " + obj);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    r = test::run(test::bin("bodygen") + " lod " + kBunny + " -o " + dir + "/bunny_jobs.bpm --jobs 0");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--jobs"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/bunny_jobs.bpm"));
    const std::string cut = dir + "/bunny_cut.bpm";
    std::filesystem::copy_file(bpm, cut, std::filesystem::copy_options::overwrite_existing);
    std::filesystem::resize_file(cut, std::filesystem::file_size(bpm) / 2);
    r = test::run(test::bin("bodygen") + " info " + cut);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace body
