// Headless replays through bodyview (llvmpipe): a tap on a model shows its label
// card, a tap on empty space hides it, and a model that fails to load is skipped
// while the others still show.
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

class KioskReplay : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::fresh_test_dir("body_kiosk_replay");
        test::write_sphere_obj(dir_ / "a.obj", -1.5f, 0.8f);
        test::write_sphere_obj(dir_ / "b.obj", 1.5f, 0.8f);
        std::ofstream(dir_ / "broken.bpm", std::ios::binary) << std::string("BPM\0xx", 6);
        std::ofstream(dir_ / "scene.json") << R"({"models": [
            {"name": "a", "file": "a.obj", "group": "left", "colour": [0.2, 0.5, 0.9], "label": {"en": {"title": "Alpha sphere",
             "description": "The left one"}}},
            {"name": "broken", "file": "broken.bpm"},
            {"name": "b", "file": "b.obj", "group": "right", "colour": [0.9, 0.5, 0.2], "label": {"en": "Beta"}}],
            "groups": [{"name": "left"}, {"name": "right"}],
            "camera": {"polar_deg": 90}})";
    }
    void TearDown() override { fs::remove_all(dir_); }

    // Runs a replay and returns the screenshot.
    render::Image play(const std::string& replay, test::RunResult* result = nullptr) {
        std::ofstream(dir_ / "input.replay") << "size 1280 800\n" << replay;
        auto r =
            test::run(test::bin("bodyview") + " --headless --size 1280x800 --scene " + (dir_ / "scene.json").string() +
                      " --replay " + (dir_ / "input.replay").string() + " --screenshot " + (dir_ / "out.png").string());
        if (result) *result = r;
        EXPECT_EQ(r.exit_code, 0) << r.output;
        auto img = render::read_png((dir_ / "out.png").string());
        EXPECT_TRUE(img) << r.output;
        return img ? img.value() : render::Image{};
    }
    // Pixels close to the selection stripe's purple in a rectangle.
    static size_t purple(const render::Image& img, int x0, int y0, int x1, int y1) {
        size_t n = 0;
        for (int y = y0; y < y1 && y < img.height; ++y) {
            for (int x = x0; x < x1 && x < img.width; ++x) {
                const uint8_t* p = img.at(x, y);
                n += std::abs(p[0] - 140) < 30 && std::abs(p[1] - 64) < 30 && std::abs(p[2] - 204) < 30;
            }
        }
        return n;
    }
    fs::path dir_;
};

TEST_F(KioskReplay, TapShowsTheLabelCardAndTapOnEmptyHidesIt) {
    if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
    test::RunResult r;
    // The left sphere is at (493, 400) at the home view: 1.5 units left of a
    // scene of radius 2.3 framed to fill 60% of a 40-degree view.
    const render::Image shown = play("0.2 down 1 493 400\n0.3 up 1 493 400\n1.0 end\n", &r);
    EXPECT_NE(r.output.find("broken: skipped"), std::string::npos) << r.output;
    ASSERT_EQ(shown.width, 1280);
    // The card's purple stripe sits at the left edge of the lower half.
    EXPECT_GT(purple(shown, 0, 400, 40, 800), 200u);
    const render::Image hidden =
        play("0.2 down 1 493 400\n0.3 up 1 493 400\n0.8 down 1 640 80\n0.9 up 1 640 80\n1.5 end\n");
    EXPECT_LT(purple(hidden, 0, 400, 40, 800), 10u);
}

TEST_F(KioskReplay, ABrokenModelLeavesTheOthersOnScreen) {
    const render::Image img = play("0.5 end\n");
    // Both spheres drawn: bluish pixels on the left half, orange ones on the right.
    size_t blue = 0, orange = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            if (x < 640 && p[2] > p[0] + 40) ++blue;
            if (x >= 640 && p[0] > p[2] + 40) ++orange;
        }
    }
    EXPECT_GT(blue, 500u);
    EXPECT_GT(orange, 500u);
}

// Bluish and near-black pixels in a box.
void count(const render::Image& img, int x0, int y0, int x1, int y1, size_t& blue, size_t& ink) {
    blue = ink = 0;
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            const uint8_t* p = img.at(x, y);
            blue += p[2] > p[0] + 40;
            ink += p[0] < 80 && p[1] < 80 && p[2] < 80;
        }
    }
}

TEST_F(KioskReplay, GroupStyleButtonTurnsTheSelectedGroupToLines) {
    // Select the left sphere, press the "Group" style button (fourth in the right
    // column at 1280x800: 72-pixel buttons, 10-pixel gaps; smooth -> lines), then
    // tap empty space to deselect (a selection is drawn purple in any style).
    const std::string select = "0.2 down 1 493 400\n0.3 up 1 493 400\n";
    const std::string deselect = "0.8 down 1 640 80\n0.9 up 1 640 80\n1.0 end\n";
    const render::Image before = play(select + deselect);
    const render::Image after = play(select + "0.5 down 2 1190 292\n0.55 up 2 1190 292\n" + deselect);
    size_t blue_before, ink_before, blue_after, ink_after;
    count(before, 430, 330, 560, 470, blue_before, ink_before);
    count(after, 430, 330, 560, 470, blue_after, ink_after);
    EXPECT_GT(blue_before, 1000u);
    EXPECT_LT(blue_after, blue_before / 10);  // paper-white fill
    EXPECT_GT(ink_after, 100u);               // with a dark outline
    // The other group keeps its smooth orange.
    size_t orange = 0;
    for (int y = 340; y < 460; ++y) {
        for (int x = 720; x < 850; ++x) orange += after.at(x, y)[0] > after.at(x, y)[2] + 40;
    }
    EXPECT_GT(orange, 1000u);
}

size_t colour_pixels(const render::Image& img, bool blue) {
    size_t n = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < 1100; ++x) {  // left of the control column
            const uint8_t* p = img.at(x, y);
            n += blue ? p[2] > p[0] + 40 : p[0] > p[2] + 40;
        }
    }
    return n;
}

TEST_F(KioskReplay, OrbitPutsOneSphereBehindTheOtherAndPinchEnlargesThem) {
    const render::Image home = play("0.3 end\n");
    // Drag 157 px left to right: the camera turns 1.57 rad to look along +x, so
    // the blue sphere at x = -1.5 hides the orange one at x = +1.5.
    const render::Image orbited =
        play("0.1 down 1 300 150\n0.2 move 1 380 150\n0.3 move 1 457 150\n0.4 up 1 457 150\n0.6 end\n");
    EXPECT_GT(colour_pixels(home, false), 1000u);
    EXPECT_LT(colour_pixels(orbited, false), colour_pixels(home, false) / 10);
    EXPECT_GT(colour_pixels(orbited, true), colour_pixels(home, true));  // closer to the eye
    // Pinch the fingers twice as far apart: the spheres cover about four times the pixels.
    const render::Image pinched = play(
        "0.1 down 1 540 200\n0.1 down 2 740 200\n0.2 move 1 440 200\n0.2 move 2 840 200\n"
        "0.3 up 1 440 200\n0.3 up 2 840 200\n0.5 end\n");
    const double ratio = static_cast<double>(colour_pixels(pinched, false)) / colour_pixels(home, false);
    EXPECT_GT(ratio, 3.0);
    EXPECT_LT(ratio, 5.0);
}

TEST_F(KioskReplay, AdminCornerTapsAreTheWayOut) {
    test::RunResult r;
    // Five taps in the top-left corner within 3 s; without them the replay would run to 60 s.
    (void)play(
        "0.2 down 1 10 10\n0.3 up 1 10 10\n0.5 down 1 10 10\n0.6 up 1 10 10\n0.8 down 1 10 10\n"
        "0.9 up 1 10 10\n1.1 down 1 10 10\n1.2 up 1 10 10\n1.4 down 1 10 10\n1.5 up 1 10 10\n60 end\n",
        &r);
    EXPECT_NE(r.output.find("admin exit"), std::string::npos) << r.output;
}

// The lowest and highest rows holding bluish pixels in the left half (the left sphere), or -1.
std::pair<int, int> blue_rows(const render::Image& img) {
    int top = -1, bottom = -1;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < 640; ++x)
            if (img.at(x, y)[2] > img.at(x, y)[0] + 40) {
                if (top < 0) top = y;
                bottom = y;
            }
    return {top, bottom};
}

TEST_F(KioskReplay, CutButtonAndDragRemoveTheUpperHalvesThroughBodyview) {
    // The Cut button is the eighth row of the right column at 1280x800
    // (72-pixel buttons, 10-pixel gaps): centre (1190, 620). Axial preset:
    // the plane y = 0 through the spheres' centres (row 400), the upper halves removed.
    const auto [top0, bottom0] = blue_rows(play("0.3 end\n"));
    const auto [top1, bottom1] = blue_rows(play("0.2 down 1 1190 620\n0.25 up 1 1190 620\n0.6 end\n"));
    ASSERT_GE(top0, 0);
    ASSERT_GE(top1, 0);
    EXPECT_LT(top0, 360);  // the whole sphere: about 400 - 62
    EXPECT_GT(top1, 390);  // only the lower half
    EXPECT_NEAR(bottom1, bottom0, 2);
    // A one-finger drag 60 px down moves the plane down with it.
    const auto [top2, bottom2] = blue_rows(
        play("0.2 down 1 1190 620\n0.25 up 1 1190 620\n0.4 down 1 300 300\n0.45 move 1 300 330\n0.5 move 1 300 360\n"
             "0.55 up 1 300 360\n0.8 end\n"));
    EXPECT_NEAR(top2, top1 + 60, 4);
    EXPECT_NEAR(bottom2, bottom0, 2);
}

}  // namespace
}  // namespace body
