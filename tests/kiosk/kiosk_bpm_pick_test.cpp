// Picking a streamed .bpm model once its detail has all arrived, when the
// renderer's element buffer holds the only copy of its index array (the kiosk
// hands it over; picking reads the buffer back): a tap selects the model
// under it, a tap on empty space selects nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
#include "kiosk/render/image.h"
#include "shared/obj_io.h"
#include "tests/common/replay_fixture.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

namespace fs = std::filesystem;

// Selection purple (transparent over the model): blue and red well above green.
size_t purple(const render::Image& img, int x0, int y0, int x1, int y1) {
    size_t n = 0;
    for (int y = y0; y < y1 && y < img.height; ++y) {
        for (int x = x0; x < x1 && x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            n += p[2] > p[1] + 60 && p[0] > p[1] + 30;
        }
    }
    return n;
}

class KioskBpmPick : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_kiosk_bpm_pick");
        for (const auto& [name, cx] : {std::pair{"a", -1.5f}, std::pair{"b", 1.5f}}) {
            test::write_sphere_obj(dir_ / (std::string(name) + ".obj"), cx, 0.8f, 24);
            const auto r = test::run(test::bin("bodygen") + " lod " + (dir_ / (std::string(name) + ".obj")).string() +
                                     " -o " + (dir_ / (std::string(name) + ".bpm")).string());
            ASSERT_EQ(r.exit_code, 0) << r.output;
        }
        std::ofstream(dir_ / "scene.json") << R"({"models": [
            {"name": "a", "file": "a.bpm", "colour": [0.9, 0.6, 0.1]},
            {"name": "b", "file": "b.bpm", "colour": [0.9, 0.6, 0.1]}],
            "camera": {"polar_deg": 90}})";
    }
    void TearDown() override { fs::remove_all(dir_); }

    render::Image play(const std::string& replay) {
        std::ofstream(dir_ / "input.replay") << "size 1280 800\n" << replay;
        auto r =
            test::run(test::bin("bodyview") + " --headless --size 1280x800 --scene " + (dir_ / "scene.json").string() +
                      " --replay " + (dir_ / "input.replay").string() + " --screenshot " + (dir_ / "out.png").string());
        EXPECT_EQ(r.exit_code, 0) << r.output;
        auto img = render::read_png((dir_ / "out.png").string());
        EXPECT_TRUE(img) << r.output;
        return img ? img.value() : render::Image{};
    }
    fs::path dir_;
};

TEST_F(KioskBpmPick, TapSelectsTheModelUnderIt) {
    // The left sphere is at (493, 400), the right one at (787, 400) at the home
    // view. The tap comes after the streams have ended (small files: at once).
    const render::Image none = play("0.6 down 1 640 80\n0.7 up 1 640 80\n1.0 end\n");
    const render::Image left = play("0.6 down 1 493 400\n0.7 up 1 493 400\n1.0 end\n");
    ASSERT_EQ(left.width, 1280);
    EXPECT_LT(purple(none, 400, 300, 900, 500), 50u);
    EXPECT_GT(purple(left, 430, 340, 560, 460), 2000u);  // the left sphere turned purple
    EXPECT_LT(purple(left, 720, 340, 850, 460), 50u);    // the right one did not
}

}  // namespace
}  // namespace body
