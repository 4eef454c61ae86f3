// The authoring window's edits reach the picture in the frame that made them
// (headless, llvmpipe): a replay ends with the edit's last event, so its
// screenshot is the first frame drawn after the edit. Adding a model (which
// uploads that model alone), removing it, a colour and a style each show
// there. Then the manipulation sphere: a pin dragged along the surface, an
// arcball rotate and a rim scale with Ctrl snapping, and Pack from the window.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../cli/cli_test.h"
#include "kiosk/render/image.h"
#include "shared/atomic_file.h"
#include "shared/obj_io.h"
#include "tests/common/replay_fixture.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

namespace fs = std::filesystem;

class AuthorFrames : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override {
        if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
        dir = test::fresh_test_dir("body_author_frames");
        test::write_sphere_obj(dir / "a.obj", -1.5f, 0.8f);
        test::write_sphere_obj(dir / "b.obj", 1.5f, 0.8f);
        test::write_sphere_obj(dir / "c.obj", 0.0f, 0.5f);
    }
    void TearDown() override {
        if (!dir.empty() && !HasFailure()) fs::remove_all(dir);
    }
    // Runs the author on a and b with `replay`; the last frame's picture.
    render::Image run(const std::string& name, const std::string& replay) {
        std::ofstream(dir / (name + ".replay")) << replay;
        const std::string png = (dir / (name + ".png")).string();
        auto r = test::run(test::bin("bodyview") + " --author " + (dir / "exhibit").string() + "/ " +
                           (dir / "a.obj").string() + " " + (dir / "b.obj").string() +
                           " --headless --size 1280x800 --replay " + (dir / (name + ".replay")).string() +
                           " --screenshot " + png);
        EXPECT_EQ(r.exit_code, 0) << r.output;
        auto img = render::read_png(png);
        EXPECT_TRUE(img) << r.output;
        return img ? img.value() : render::Image{};
    }
};

bool same(const uint8_t* a, const uint8_t* b) {
    return std::abs(a[0] - b[0]) <= 8 && std::abs(a[1] - b[1]) <= 8 && std::abs(a[2] - b[2]) <= 8;
}

// New scene rows: 3 "(no group)", 4 a, 5 b, 6 add model; with a selected 10 "Model: a", 14 colour, 18 style.
// The view is centred 200 px right of the screen's centre: a at x ~ 700, c (added) at 840, b at ~ 980.
TEST_F(AuthorFrames, AddRemoveColourAndStyleShowInTheFrameOfTheEdit) {
    test::AuthorScript base;
    base.row(4, 100);  // a selected, then not: every model in its own colour and style
    base.t -= 0.07;
    base.key(256);
    const render::Image before = run("before", base.done());
    ASSERT_GT(before.width, 0);

    test::AuthorScript add;
    add.row(4, 100);
    add.row(6);
    add.type((dir / "c.obj").string());
    add.key(265);  // Enter: the edit
    const render::Image added = run("added", add.done());
    ASSERT_GT(added.width, 0);
    EXPECT_FALSE(same(before.at(840, 400), added.at(840, 400)));  // c is drawn in that frame

    test::AuthorScript remove;
    remove.row(4, 100);
    remove.row(6);
    remove.type((dir / "c.obj").string());
    remove.key(265);
    remove.key(258);  // Delete: c (selected once added) is removed
    const render::Image removed = run("removed", remove.done());
    EXPECT_TRUE(same(before.at(840, 400), removed.at(840, 400)));

    // The colour of a: sample a's centre on the picture with a selected.
    int ax = 0;
    for (int x = 420; x < 840 && !ax; ++x)
        if (!same(before.at(x, 400), before.at(830, 400))) ax = x + 40;
    ASSERT_GT(ax, 0);
    test::AuthorScript colour;
    colour.row(4, 100);
    colour.row(14);
    colour.key('A', "ctrl");
    colour.type("0 1 0");
    colour.key(265);
    colour.t -= 0.05;
    colour.key(256);  // Esc in the same frame: deselected, a is drawn in its own colour
    const render::Image green = run("colour", colour.done());
    EXPECT_FALSE(same(before.at(ax, 400), green.at(ax, 400)));
    EXPECT_GT(green.at(ax, 400)[1], green.at(ax, 400)[0]);  // greener than red now

    test::AuthorScript style;
    style.row(4, 100);
    style.mouse("down", 284, 26 * 18 + 13);  // style: smooth -> wireframe, on the press
    style.t -= 0.02;
    style.mouse("up", 284, 26 * 18 + 13);
    style.t -= 0.02;
    style.key(256);  // deselected in the frame of the edit
    const render::Image wire = run("style", style.done());
    size_t changed = 0;
    for (int x = ax - 60; x < ax + 60; ++x) changed += !same(before.at(x, 400), wire.at(x, 400));
    EXPECT_GT(changed, 10u);
}

// One sphere a: a pin placed, packed, dragged; then rotate and scale on the manipulation sphere with Ctrl.
TEST_F(AuthorFrames, PinDragArcballRotateRimScaleSnapAndPack) {
    test::write_sphere_obj(dir / "one.obj", 0.0f, 1.0f);
    test::AuthorScript s;
    s.click(840, 400);  // selects the sphere, marks the point for Add pin
    // Rows: 3 "(no group)", 4 one, 5 add model, 6 buttons, 7 Tours, 8 Add tour, 9 "Model: one", ... 22 Add pin.
    s.row(22, 200);
    s.key('P', "ctrl");                            // Pack: exhibit-bundle/ holds the pin where it was put
    s.drag(840, 400, 880, 430);                    // the pin's marker dragged along the surface
    s.drag(840, 400, 880, 400, "alt");             // arcball: a turn about the view's up axis
    s.drag(845, 400, 862, 400, "alt shift ctrl");  // rim scale: 22/5 -> 4.4 -> snapped to 4.4
    s.key('S', "ctrl");
    std::ofstream(dir / "tools.replay") << s.done();
    auto r = test::run(test::bin("bodyview") + " --author " + (dir / "exhibit").string() + "/ " +
                       (dir / "one.obj").string() + " --headless --size 1280x800 --replay " +
                       (dir / "tools.replay").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("unsaved"), std::string::npos) << r.output;
    const auto packed_text = read_file((dir / "exhibit-bundle" / "scene.json").string());
    ASSERT_TRUE(packed_text) << r.output;
    const auto packed = nlohmann::json::parse(packed_text.value());
    const auto saved = nlohmann::json::parse(read_file((dir / "exhibit" / "scene.json").string()).value());
    EXPECT_TRUE(fs::exists(dir / "exhibit-bundle" / "models" / "one.obj"));
    ASSERT_EQ(packed["models"][0]["pins"].size(), 1u) << packed_text.value();
    ASSERT_EQ(saved["models"][0]["pins"].size(), 1u);
    const auto& a0 = packed["models"][0]["pins"][0]["anchor"];
    const auto& a1 = saved["models"][0]["pins"][0]["anchor"];
    EXPECT_NE(a0, a1);  // dragged
    EXPECT_NEAR(std::hypot(a1[0].get<double>(), a1[1].get<double>(), a1[2].get<double>()), 1.0, 0.03) << a1;

    const auto& t = saved["models"][0]["transform"];
    const double ry = t["rotate_deg"][1].get<double>();
    EXPECT_GT(std::abs(ry), 5.0) << t;  // turned about the vertical
    EXPECT_NEAR(t["rotate_deg"][0].get<double>(), 0.0, 1.0) << t;
    const double s_ = t["scale"].get<double>();
    EXPECT_GT(s_, 1.5) << t;
    EXPECT_NEAR(s_ * 10.0, std::round(s_ * 10.0), 1e-3) << t;  // snapped to 0.1
    // The sphere's centre (the model's origin here) stays put through turn and scale.
    EXPECT_NEAR(std::hypot(t["translate"][0].get<double>(), t["translate"][2].get<double>()), 0.0, 1e-3) << t;
}

// An STL on the command line: converted once into the new scene's models/ folder, and drawn.
TEST_F(AuthorFrames, StlOnTheCommandLineBecomesOneBpmInTheScenesModelsFolder) {
    const Mesh sphere = test::uv_sphere(12, 24, Vec3(0.0), 1.0);
    ASSERT_TRUE(write_obj((dir / "ball.obj").string(), std::span<const Mesh>(&sphere, 1)).ok());
    // bodygen export writes the STL, as an atlas's meshes would come.
    auto e = test::run(test::bin("bodygen") + " export " + (dir / "ball.obj").string() + " -o " +
                       (dir / "ball.stl").string() + " --quiet");
    ASSERT_EQ(e.exit_code, 0) << e.output;
    test::AuthorScript s;
    s.key('S', "ctrl");
    std::ofstream(dir / "stl.replay") << s.done();
    auto r = test::run(test::bin("bodyview") + " --author " + (dir / "exhibit").string() + "/ " +
                       (dir / "ball.stl").string() + " --headless --size 1280x800 --replay " +
                       (dir / "stl.replay").string() + " --screenshot " + (dir / "stl.png").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto j = nlohmann::json::parse(read_file((dir / "exhibit" / "scene.json").string()).value());
    EXPECT_EQ(j["models"][0]["file"], "models/ball.bpm");
    size_t files = 0;
    for (const auto& f : fs::directory_iterator(dir / "exhibit" / "models")) files += f.is_regular_file();
    EXPECT_EQ(files, 1u);
    auto img = render::read_png((dir / "stl.png").string());
    ASSERT_TRUE(img);
    EXPECT_FALSE(same(img.value().at(840, 400), img.value().at(1270, 10)));  // the ball, not the background
}

}  // namespace
}  // namespace body
