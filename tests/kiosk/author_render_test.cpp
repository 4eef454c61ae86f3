// The authoring window end to end (headless, llvmpipe): a replay builds a scene
// from two model files, edits it through the side panel (style, colour, a
// German title typed character by character, an undone scale, a new group and
// a member for it, the start view from the camera), saves it with Ctrl+S and
// previews it; the saved scene.json holds exactly those edits, and the kiosk
// started on the saved scene shows the same picture as the author's preview.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
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

double mismatch(const render::Image& a, const render::Image& b) {
    if (a.width != b.width || a.height != b.height) return 1.0;
    size_t differ = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (std::abs(a.at(x, y)[c] - b.at(x, y)[c]) > 8) {
                    ++differ;
                    break;
                }
    return static_cast<double>(differ) / (static_cast<double>(a.width) * a.height);
}

TEST(AuthorReplay, BuildEditSaveAndTheKioskShowsThePreview) {
    if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
    const fs::path dir = test::fresh_test_dir("body_author_replay");
    test::write_sphere_obj(dir / "a.obj", -1.5f, 0.8f);
    test::write_sphere_obj(dir / "b.obj", 1.5f, 0.8f);
    const fs::path bundle = dir / "exhibit";

    test::AuthorScript s;
    // New scene: rows 3 "(no group)", 4 a, 5 b, 6 add model, 7 Add group | Remove, 8 "Tours", 9 Add tour, 10 "Model:
    // a", then name, file, group, colour, translate, rotate, scale, style, LOD, reset, title [en], description [en].
    s.row(4, 100);             // select a
    s.row(18);                 // style: smooth -> wireframe
    s.set(14, U"1 0 0");       // colour
    s.set(21, U"Großhirn");    // title [en]
    s.set(17, U"2");           // scale 2 ...
    s.key('Z', "ctrl");        // ... undone
    s.key('Z', "ctrl shift");  // redo, then undo again: the redo stack works both ways
    s.key('Z', "ctrl");
    s.row(7, 100);  // Add group: "group 1", selected
    // Rows now: 3 "group 1", 4 "(no group)", 5 a, 6 b, 7 add model, 8 buttons, 9 "Tours", 10 Add tour,
    // 11 "Group: group 1".
    s.row(6, 100);  // select b: 11 "Model: b", 12 name, 13 file, 14 group
    s.row(14);      // group: none -> group 1
    // Shift+drag on b moves it with the manipulation sphere: one "move" command on release.
    // b is at x 769 in a centred view; the author's view is centred right of the 400-px panel.
    s.out << s.t << " mouse-down left 969 400 shift\n";
    for (int i = 1; i <= 6; ++i) s.out << s.t + 0.02 * i << " mouse-move " << 969 + 10 * i << " 400 shift\n";
    s.out << s.t + 0.14 << " mouse-up left 1029 400 shift\n";
    s.t += 0.2;
    s.out << s.t << " wheel 800 400 1\n";
    s.t += 0.1;
    s.key('V');  // start view from the (zoomed) camera
    s.key('S', "ctrl");
    s.key('P');  // preview the kiosk
    s.out << s.t + 0.2 << " end\n";
    std::ofstream(dir / "author.replay") << s.out.str();

    auto r = test::run(test::bin("bodyview") + " --author " + bundle.string() + "/ " + (dir / "a.obj").string() + " " +
                       (dir / "b.obj").string() + " --headless --size 1280x800 --replay " +
                       (dir / "author.replay").string() + " --screenshot " + (dir / "author.png").string() +
                       " --preview-screenshot " + (dir / "preview.png").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("unsaved"), std::string::npos) << r.output;

    auto text = read_file((bundle / "scene.json").string());
    ASSERT_TRUE(text) << r.output;
    const auto j = nlohmann::json::parse(text.value());
    ASSERT_EQ(j["models"].size(), 2u) << text.value();
    const auto& a = j["models"][0];
    EXPECT_EQ(a["name"], "a");
    EXPECT_EQ(a["file"], (dir / "a.obj").string());  // outside the bundle: absolute (bodygen pack copies it in)
    EXPECT_EQ(a["style"], "wireframe");
    EXPECT_EQ(a["colour"], nlohmann::json::parse("[1, 0, 0]"));
    EXPECT_EQ(a["label"]["en"]["title"], "Großhirn");
    EXPECT_EQ(a["transform"]["scale"], 1.0);
    EXPECT_FALSE(a.contains("group"));
    EXPECT_EQ(j["models"][1]["group"], "group 1");
    EXPECT_GT(j["models"][1]["transform"]["translate"][0].get<double>(), 0.1);  // dragged right
    EXPECT_EQ(j["models"][0]["transform"]["translate"][0].get<double>(), 0.0);
    ASSERT_EQ(j["groups"].size(), 1u);
    EXPECT_EQ(j["groups"][0]["name"], "group 1");
    EXPECT_GT(j["camera"]["distance"].get<double>(), 0.0);  // the start view was set

    // The author's window shows the panel over the view.
    auto author = render::read_png((dir / "author.png").string());
    ASSERT_TRUE(author);
    EXPECT_EQ(author.value().at(200, 790)[0], author.value().at(300, 780)[0]);  // the panel's flat fill
    EXPECT_NE(author.value().at(200, 790)[0], author.value().at(1000, 790)[0]);

    // The kiosk on the saved bundle, on the same clock as the preview.
    std::ofstream(dir / "kiosk.replay") << "size 1280 800\n0.5 end\n";
    auto k = test::run(test::bin("bodyview") + " " + bundle.string() + "/ --headless --size 1280x800 --replay " +
                       (dir / "kiosk.replay").string() + " --screenshot " + (dir / "kiosk.png").string());
    ASSERT_EQ(k.exit_code, 0) << k.output;
    auto preview = render::read_png((dir / "preview.png").string());
    auto kiosk = render::read_png((dir / "kiosk.png").string());
    ASSERT_TRUE(preview) << r.output;
    ASSERT_TRUE(kiosk) << k.output;
    EXPECT_LT(mismatch(preview.value(), kiosk.value()), 0.001);
    // Not trivially equal: the edits are on screen (wireframe a is not the red of a smooth fill).
    EXPECT_GT(mismatch(preview.value(), author.value()), 0.01);
    if (!::testing::Test::HasFailure() && !std::getenv("BODY_KEEP_TEST_DIR")) fs::remove_all(dir);
}

// The same window on a desktop: GLFW under Xvfb (a real X server, the glfw
// backend's events path), driven by a replay; the saved file holds the edits.
TEST(AuthorReplay, GlfwWindowUnderXvfbSavesTheEdits) {
    if (!fs::exists("/usr/bin/xvfb-run")) GTEST_SKIP() << "needs xvfb (xvfb-run)";
    if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
    const fs::path dir = test::fresh_test_dir("body_author_xvfb");
    test::write_sphere_obj(dir / "a.obj", 0.0f, 1.0f);
    test::AuthorScript s;
    // a (rows: 3 "(no group)", 4 a, 5 add model, 6 buttons, 7 "Tours", 8 Add tour, 9 "Model: a", 10 name ...)
    s.row(4, 100);
    s.row(17);                      // style: smooth -> wireframe
    s.set(20, U"Hippocampus ΑΒΓ");  // title [en]
    s.key('S', "ctrl");
    s.out << s.t + 0.2 << " end\n";
    std::ofstream(dir / "author.replay") << s.out.str();
    auto r = test::run("/usr/bin/xvfb-run -a -s '-screen 0 1280x800x24' " + test::bin("bodyview") + " --author " +
                       (dir / "exhibit").string() + "/ " + (dir / "a.obj").string() +
                       " --platform glfw --windowed --size 1280x800 --replay " + (dir / "author.replay").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto text = read_file((dir / "exhibit" / "scene.json").string());
    ASSERT_TRUE(text) << r.output;
    const auto j = nlohmann::json::parse(text.value());
    EXPECT_EQ(j["models"][0]["style"], "wireframe");
    EXPECT_EQ(j["models"][0]["label"]["en"]["title"], "Hippocampus ΑΒΓ");
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

// A pin where a click hit the model, and a tour step from the view: the author
// loop's picking and camera reach the saved file (kiosk/author/author_run.cpp).
TEST(AuthorReplay, PinAtTheClickedPointAndAStepFromTheView) {
    if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
    const fs::path dir = test::fresh_test_dir("body_author_pins");
    test::write_sphere_obj(dir / "a.obj", 0.0f, 1.0f);
    test::AuthorScript s;
    // The sphere fills the view's centre, 200 px right of the screen's (the panel is 400 px wide).
    s.click(840, 400);  // selects a and marks the point hit
    // Rows: 7 "Tours", 8 Add tour, 9 "Model: a", ... 20 title [en], 21 description [en], 22 Add pin.
    s.row(22, 200);
    s.row(8, 200);      // Add tour: "tour 1" selected (8 its row, 9 "step 1", 10 + step, 11 Add tour)
    s.click(840, 400);  // a selected again: 8 "tour 1", 9 + step
    s.out << s.t << " wheel 840 400 1\n";  // a closer view for the step
    s.t += 0.1;
    s.row(9, 200);  // + step to tour 1 from the view
    s.key('S', "ctrl");
    s.out << s.t + 0.2 << " end\n";
    std::ofstream(dir / "author.replay") << s.out.str();
    auto r =
        test::run(test::bin("bodyview") + " --author " + (dir / "exhibit").string() + "/ " + (dir / "a.obj").string() +
                  " --headless --size 1280x800 --replay " + (dir / "author.replay").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output.find("unsaved"), std::string::npos) << r.output;
    auto text = read_file((dir / "exhibit" / "scene.json").string());
    ASSERT_TRUE(text) << r.output;
    const auto j = nlohmann::json::parse(text.value());
    ASSERT_EQ(j["models"][0]["pins"].size(), 1u) << text.value();
    const auto& anchor = j["models"][0]["pins"][0]["anchor"];
    const double len = std::hypot(anchor[0].get<double>(), anchor[1].get<double>(), anchor[2].get<double>());
    EXPECT_NEAR(len, 1.0, 0.03) << anchor;  // on the unit sphere's (tessellated) surface
    ASSERT_EQ(j["tours"].size(), 1u) << text.value();
    const auto& steps = j["tours"][0]["steps"];
    ASSERT_EQ(steps.size(), 2u) << text.value();
    EXPECT_EQ(steps[1]["select"], "a");
    EXPECT_EQ(steps[1]["visible"], nlohmann::json::parse(R"(["a"])"));
    ASSERT_TRUE(steps[1].contains("camera")) << steps[1];
    EXPECT_GT(steps[1]["camera"]["distance"].get<double>(), 0.0);
    EXPECT_TRUE(steps[1]["camera"].contains("azimuth_deg"));
    if (!::testing::Test::HasFailure()) fs::remove_all(dir);
}

}  // namespace
}  // namespace body
