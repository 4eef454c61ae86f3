// GL faults in the kiosk loop, put in through KioskHooks::gl_health (llvmpipe
// raises neither on demand): GL_OUT_OF_MEMORY lowers the detail drawn and the
// kiosk goes on; a lost context ends the loop with exit 1 at that frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
#include "kiosk/app/kiosk_run.h"
#include "shared/obj_io.h"
#include "shared/scene/scene.h"
#include "tests/common/headless_surface.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body::kiosk {
namespace {

namespace fs = std::filesystem;

class KioskGlFaults : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_kiosk_gl_faults");
        const Mesh m = test::uv_sphere(48, 96, Vec3(0.0, 0.0, 0.0), 0.8);
        ASSERT_TRUE(write_obj((dir_ / "s.obj").string(), std::span<const Mesh>(&m, 1)).ok());
        const auto r =
            test::run(test::bin("bodygen") + " lod " + (dir_ / "s.obj").string() + " -o " + (dir_ / "s.bpm").string());
        ASSERT_EQ(r.exit_code, 0) << r.output;
        std::ofstream(dir_ / "scene.json") << R"({"models": [{"name": "s", "file": "s.bpm"}]})";
        std::ofstream(dir_ / "idle.replay") << "1.0 end\n";  // 61 frames, every detail loaded first
        auto scene = scene::read_scene((dir_ / "scene.json").string());
        ASSERT_TRUE(scene) << scene.error().message;
        scene_ = std::move(scene).value();
        auto surface = body::test::headless_surface();
        if (!surface) GTEST_SKIP() << "no headless GL: " << surface.error().message;
        surface_ = std::move(surface).value();
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs the replay with `fault` put in at frame `at`; the triangles of each frame in `drawn`.
    int run(platform::GlHealth fault, long at, std::vector<size_t>& drawn) {
        KioskRunOptions o;
        o.replay = (dir_ / "idle.replay").string();
        o.auto_lod = false;  // every model at ratio 1 x the cap
        long frame = 0;
        o.hooks.gl_health = [&] { return frame++ == at ? fault : platform::GlHealth{}; };
        o.hooks.frame_done = [&](const FrameReport& r) {
            drawn.push_back(r.triangles);
            return true;
        };
        return run_kiosk(*surface_, scene_, o);
    }

    fs::path dir_;
    scene::Scene scene_;
    std::unique_ptr<platform::Surface> surface_;
};

TEST_F(KioskGlFaults, OutOfMemoryLowersTheDetailAndTheKioskGoesOn) {
    std::vector<size_t> healthy, starved;
    ASSERT_EQ(run({}, -1, healthy), 0);
    platform::GlHealth oom;
    oom.errors = 1;
    oom.out_of_memory = true;
    oom.first_error = GL_OUT_OF_MEMORY;
    ASSERT_EQ(run(oom, 5, starved), 0);
    ASSERT_EQ(healthy.size(), starved.size());  // it ran to the end
    EXPECT_LT(starved.back(), healthy.back() * 6 / 10);
    EXPECT_GT(starved.back(), 0u);
}

TEST_F(KioskGlFaults, ALostContextEndsTheLoopWithExitOne) {
    std::vector<size_t> drawn;
    platform::GlHealth lost;
    lost.reset_status = 0x8253;  // GL_GUILTY_CONTEXT_RESET (GLES 3.2, GL_EXT_robustness)
    EXPECT_EQ(run(lost, 5, drawn), 1);
    EXPECT_EQ(drawn.size(), 6u);  // frames 0..5
}

}  // namespace
}  // namespace body::kiosk
