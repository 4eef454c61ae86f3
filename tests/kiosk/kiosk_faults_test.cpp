// Faults while the kiosk runs (bodyview headless, llvmpipe): a .bpm that ends
// or goes bad in the middle of its detail stream is reported in one line naming
// the model, the rest of the scene keeps streaming and the kiosk keeps drawing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
#include "shared/obj_io.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

namespace fs = std::filesystem;

class KioskFaults : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_kiosk_faults");
        for (const char* name : {"good", "bad"}) {
            const Mesh m = test::uv_sphere(48, 96, Vec3(name[0] == 'g' ? -1.5 : 1.5, 0.0, 0.0), 0.8);
            const std::string obj = (dir_ / name).string() + ".obj";
            ASSERT_TRUE(write_obj(obj, std::span<const Mesh>(&m, 1)).ok());
            const auto r = test::run(test::bin("bodygen") + " lod " + obj + " -o " + (dir_ / name).string() + ".bpm");
            ASSERT_EQ(r.exit_code, 0) << r.output;
        }
        std::ofstream(dir_ / "scene.json") << R"({"models": [{"name": "good", "file": "good.bpm"},
            {"name": "bad", "file": "bad.bpm"}]})";
        size_ = fs::file_size(dir_ / "bad.bpm");
    }
    void TearDown() override { fs::remove_all(dir_); }
    test::RunResult run_kiosk() {
        return test::run(test::bin("bodyview") + " --headless --size 320x200 --frames 90 " + dir_.string() + "/");
    }
    fs::path dir_;
    uintmax_t size_ = 0;
};

TEST_F(KioskFaults, ATruncatedDetailStreamIsReportedAndTheKioskGoesOn) {
    fs::resize_file(dir_ / "bad.bpm", size_ * 7 / 10);
    const auto r = run_kiosk();
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("bodyview: bad: "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("bodyview: good: "), std::string::npos) << r.output;
}

TEST_F(KioskFaults, ACorruptSectionIsReportedAndTheKioskGoesOn) {
    {
        std::fstream f(dir_ / "bad.bpm", std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(static_cast<std::streamoff>(size_ * 8 / 10));
        const char junk[16] = {'\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a',
                               '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a', '\x5a'};
        f.write(junk, sizeof junk);
    }
    const auto r = run_kiosk();
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("bodyview: bad: "), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("bodyview: good: "), std::string::npos) << r.output;
}

}  // namespace
}  // namespace body
