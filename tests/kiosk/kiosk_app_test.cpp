// Replay-driven kiosk behaviour: each test scripts touches or mouse input as a
// replay, plays it at 60 Hz and asserts the resulting state.
#include "kiosk/app/kiosk_app.h"

#include <gtest/gtest.h>

#include <cmath>

#include "kiosk_test_scene.h"
#include "tests/platform/input_events.h"

namespace body::kiosk {
namespace {

using test::make_app;
using test::replay;

const Control& control(const KioskApp& app, ControlId id) {
    for (const Control& c : app.controls()) {
        if (c.id == id) return c;
    }
    ADD_FAILURE() << "no such control";
    return app.controls().front();
}

std::string tap_on(const Control& c, double t, int id = 9) {
    const float x = c.rect.x + c.rect.w / 2, y = c.rect.y + c.rect.h / 2;
    return std::to_string(t) + " down " + std::to_string(id) + " " + std::to_string(x) + " " + std::to_string(y) +
           "\n" + std::to_string(t + 0.05) + " up " + std::to_string(id) + " " + std::to_string(x) + " " +
           std::to_string(y) + "\n";
}

// Mouse input as replay text: a click (down, up 50 ms later) and a drag (down,
// move, up 100 ms apart); `mods` as in the replay format (e.g. "shift").
std::string mouse_line(double t, const std::string& what, float x, float y, const std::string& mods) {
    return std::to_string(t) + " " + what + " " + std::to_string(x) + " " + std::to_string(y) + " " + mods + "\n";
}
std::string click(double t, const std::string& button, float x, float y, const std::string& mods = "") {
    return mouse_line(t, "mouse-down " + button, x, y, mods) + mouse_line(t + 0.05, "mouse-up " + button, x, y, mods);
}
std::string drag(double t, const std::string& button, float x0, float y0, float x1, float y1,
                 const std::string& mods = "") {
    return mouse_line(t, "mouse-down " + button, x0, y0, mods) + mouse_line(t + 0.1, "mouse-move", x1, y1, mods) +
           mouse_line(t + 0.2, "mouse-up " + button, x1, y1, mods);
}
// Plays replay text that starts at `t`.
void play(KioskApp& app, double t, const std::string& text) { run_replay(app, replay(text), 60.0, t); }

// Where a scene point appears horizontally on the 1280-pixel-wide screen.
float screen_x(const KioskApp& app, const glm::vec3& p) {
    const glm::vec4 c = app.camera().projection() * app.camera().view() * glm::vec4(p, 1.0f);
    return (c.x / c.w * 0.5f + 0.5f) * 1280.0f;
}

TEST(KioskApp, StartsAtHomeFittingTheScene) {
    KioskApp app = make_app();
    app.update(0.0);
    const CameraPose& p = app.camera().pose();
    EXPECT_NEAR(p.azimuth, 0.0f, 1e-6f);
    EXPECT_NEAR(p.polar, 1.5707964f, 1e-5f);
    EXPECT_NEAR(p.target.x, 0.0f, 1e-4f);
    // Every model projects inside the screen.
    for (int i = 0; i < 3; ++i) {
        const glm::vec4 c = app.camera().projection() * app.camera().view() * glm::vec4(app.model_center(i), 1.0f);
        EXPECT_LT(std::abs(c.x / c.w), 0.9f);
    }
    EXPECT_EQ(app.selected(), -1);
    EXPECT_EQ(app.mode(), KioskMode::Interactive);
}

TEST(KioskApp, OneFingerOrbitsWithThePolarAngleClamped) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 640 400\n0.05 move 1 660 400\n0.1 move 1 700 400\n0.15 move 1 740 400\n"
                           "0.2 up 1 740 400\n"));
    EXPECT_NEAR(app.camera().pose().azimuth, -1.0f, 1e-4f);  // 100 px at 0.01 rad/px
    EXPECT_NEAR(app.camera().pose().polar, 1.5707964f, 1e-5f);
    EXPECT_EQ(app.selected(), -1);  // a drag is not a tap

    run_replay(app, replay("1.0 down 1 640 100\n1.1 move 1 640 790\n1.2 move 1 640 799\n1.3 up 1 640 799\n"), 60.0,
               1.0);
    EXPECT_FLOAT_EQ(app.camera().pose().polar, OrbitCamera::kMinPolar);
}

TEST(KioskApp, PinchZoomsByTheFingerRatioAndClamps) {
    KioskApp app = make_app();
    app.update(0.0);
    const float home = app.camera().pose().distance;
    run_replay(app, replay("0.0 down 1 540 400\n0.0 down 2 740 400\n0.1 move 1 490 400\n0.1 move 2 790 400\n"
                           "0.2 move 1 440 400\n0.2 move 2 840 400\n0.3 up 1 440 400\n0.3 up 2 840 400\n"));
    EXPECT_NEAR(app.camera().pose().distance, home / 2.0f, home * 1e-4f);
    EXPECT_NEAR(app.camera().pose().azimuth, 0.0f, 1e-6f);  // no orbit from a pinch
    EXPECT_EQ(app.selected(), -1);
    run_replay(app,
               replay("1.0 down 1 630 400\n1.0 down 2 650 400\n1.1 move 1 10 400\n1.1 move 2 1270 400\n"
                      "1.2 up 1 10 400\n1.2 up 2 1270 400\n"),
               60.0, 1.0);
    EXPECT_FLOAT_EQ(app.camera().pose().distance, app.camera().min_distance());
}

TEST(KioskApp, TwoFingerPanFollowsTheFingers) {
    KioskApp app = make_app();
    app.update(0.0);
    const float d = app.camera().pose().distance;
    const float units_per_px = 2.0f * d * std::tan(app.camera().fov_y() / 2) / 800.0f;
    run_replay(app, replay("0.0 down 1 540 400\n0.0 down 2 740 400\n0.1 move 1 590 400\n0.1 move 2 790 400\n"
                           "0.2 move 1 640 400\n0.2 move 2 840 400\n0.3 up 1 640 400\n0.3 up 2 840 400\n"));
    // Fingers moved 100 px right: the scene follows, so the target moved left.
    EXPECT_NEAR(app.camera().pose().target.x, -100.0f * units_per_px, 0.01f);
    EXPECT_NEAR(app.camera().pose().target.y, 0.0f, 1e-3f);
    EXPECT_NEAR(app.camera().pose().distance, d, d * 1e-4f);
}

TEST(KioskApp, LiftingOneOfTwoFingersDoesNotOrbit) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 540 400\n0.0 down 2 740 400\n0.1 move 2 760 400\n0.2 up 2 760 400\n"
                           "0.3 move 1 700 400\n0.4 up 1 700 400\n"));
    EXPECT_NEAR(app.camera().pose().azimuth, 0.0f, 1e-6f);
}

TEST(KioskApp, TapSelectsAndTapOnEmptyDeselects) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 640 400\n0.1 up 1 641 401\n"));
    EXPECT_EQ(app.selected(), 1);
    EXPECT_EQ(app.scene().label(app.scene().models[1], app.language()).title, "Middle");
    run_replay(app, replay("1.0 down 1 300 150\n1.1 up 1 300 150\n"), 60.0, 1.0);
    EXPECT_EQ(app.selected(), -1);
    // A long press is not a tap.
    run_replay(app, replay("2.0 down 1 640 400\n3.0 up 1 640 400\n"), 60.0, 2.0);
    EXPECT_EQ(app.selected(), -1);
}

TEST(KioskApp, DoubleTapFocusesOnTheModel) {
    KioskApp app = make_app();
    app.update(0.0);
    const float home = app.camera().pose().distance;
    // The right model: x = 100 projects right of centre.
    const std::string x = std::to_string(screen_x(app, {100, 0, 0}));
    run_replay(app, replay("0.0 down 1 " + x + " 400\n0.08 up 1 " + x + " 400\n0.2 down 1 " + x + " 400\n0.28 up 1 " +
                           x + " 400\n2.0 end\n"));
    EXPECT_EQ(app.selected(), 2);
    EXPECT_NEAR(app.camera().pose().target.x, 100.0f, 0.01f);
    EXPECT_NEAR(app.camera().pose().distance, app.camera().fit_distance(40.0f), 0.01f);
    EXPECT_LT(app.camera().pose().distance, home);
}

TEST(KioskApp, GroupStyleButtonRestylesTheSelectionsGroup) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 640 400\n0.1 up 1 640 400\n"));
    ASSERT_EQ(app.selected(), 1);
    run_replay(app, replay(tap_on(control(app, ControlId::GroupStyle), 0.5)), 60.0, 0.5);
    EXPECT_EQ(app.model(0).style, Style::Lines);
    EXPECT_EQ(app.model(1).style, Style::Lines);
    EXPECT_EQ(app.model(2).style, Style::Hatching);  // the other group is untouched
    EXPECT_EQ(app.selected(), 1);                    // tapping a control does not deselect
    run_replay(app, replay(tap_on(control(app, ControlId::Style), 1.0)), 60.0, 1.0);
    EXPECT_EQ(app.model(1).style, Style::Hatching);
    EXPECT_EQ(app.model(0).style, Style::Lines);
}

TEST(KioskApp, GroupToggleIsolateAndLanguage) {
    KioskApp app = make_app();
    app.update(0.0);
    const Control* cortex = nullptr;
    for (const Control& c : app.controls()) {
        if (c.id == ControlId::GroupToggle && c.group == 1) cortex = &c;
    }
    ASSERT_NE(cortex, nullptr);
    run_replay(app, replay(tap_on(*cortex, 0.0)));
    EXPECT_FALSE(app.visible(2));
    EXPECT_TRUE(app.visible(0));
    run_replay(app, replay(tap_on(control(app, ControlId::Language), 0.5)), 60.0, 0.5);
    EXPECT_EQ(app.language(), "de");
    EXPECT_EQ(app.scene().label(app.scene().models[0], app.language()).title, "Links");
    app.set_group_visible(1, true);
    app.select(0);
    app.toggle_isolate();
    EXPECT_TRUE(app.visible(0));
    EXPECT_FALSE(app.visible(2));
    app.toggle_isolate();
    EXPECT_TRUE(app.visible(2));
}

TEST(KioskApp, IdleAttractThenFullReset) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 640 400\n0.1 up 1 640 400\n"                         // select middle
                           "0.5 down 1 300 150\n0.6 move 1 400 150\n0.7 up 1 400 150\n"));  // orbit
    ASSERT_EQ(app.selected(), 1);
    app.set_group_style(0, Style::Wireframe);
    app.next_language();
    const float orbited = app.camera().pose().azimuth;
    EXPECT_NEAR(orbited, -1.0f, 1e-4f);

    // 4 s idle: still interactive, nothing moves.
    run_replay(app, replay("4.6 end\n"), 60.0, 0.8);
    EXPECT_EQ(app.mode(), KioskMode::Interactive);
    EXPECT_NEAR(app.camera().pose().azimuth, orbited, 1e-5f);
    // Past 5 s: attract mode turns the camera slowly.
    run_replay(app, replay("7.7 end\n"), 60.0, 4.7);
    EXPECT_EQ(app.mode(), KioskMode::Attract);
    EXPECT_NEAR(app.camera().pose().azimuth - orbited, KioskApp::kAttractRadiansPerSecond * 2.0f, 0.02f);
    EXPECT_EQ(app.selected(), 1);  // not reset yet
    // Past 10 s: everything back to the manifest's.
    run_replay(app, replay("10.8 end\n"), 60.0, 7.8);
    EXPECT_EQ(app.resets(), 1);
    EXPECT_EQ(app.selected(), -1);
    EXPECT_EQ(app.model(0).style, Style::Smooth);
    EXPECT_EQ(app.model(2).style, Style::Hatching);
    EXPECT_EQ(app.language(), "en");
    EXPECT_NEAR(app.camera().pose().azimuth, KioskApp::kAttractRadiansPerSecond * 0.1f, 0.02f);  // home + attract
    // Still attracting, reset only once per idle period; a touch wakes it up.
    run_replay(app, replay("14.0 end\n"), 60.0, 10.9);
    EXPECT_EQ(app.resets(), 1);
    run_replay(app, replay("14.1 down 1 300 150\n14.2 up 1 300 150\n"), 60.0, 14.1);
    EXPECT_EQ(app.mode(), KioskMode::Interactive);
}

TEST(KioskApp, DriftIsSmallAndMoves) {
    KioskApp app = make_app();
    float max_abs = 0.0f;
    for (double t = 0; t < 300; t += 0.5) {
        const glm::vec2 d = app.drift(t);
        max_abs = std::max({max_abs, std::abs(d.x), std::abs(d.y)});
    }
    EXPECT_LE(max_abs, KioskApp::kDriftPx);
    EXPECT_GT(max_abs, 1.0f);
    EXPECT_NE(app.drift(10.0), app.drift(40.0));
}

Control corner() {
    Control c;
    c.rect = Rect{0, 0, 40, 40};
    return c;
}

TEST(KioskApp, OnlyTheAdminGestureExits) {
    KioskApp app = make_app();
    std::string taps;
    for (int i = 0; i < 4; ++i) taps += tap_on(corner(), 0.3 * i);
    run_replay(app, replay(taps));
    EXPECT_FALSE(app.exit_requested());  // 4 of 5
    run_replay(app, replay("5.0 key 256\n5.1 down 1 1270 790\n5.2 up 1 1270 790\n"), 60.0, 5.0);
    EXPECT_FALSE(app.exit_requested());  // Escape and other corners do nothing
    taps.clear();
    for (int i = 0; i < 5; ++i) taps += tap_on(corner(), 6.0 + 0.3 * i);
    run_replay(app, replay(taps), 60.0, 6.0);
    EXPECT_TRUE(app.exit_requested());
}

TEST(KioskApp, ThesisMouseBindings) {
    KioskApp app = make_app();
    app.update(0.0);
    const float home = app.camera().pose().distance;
    // Left drag rotates.
    play(app, 0.0, drag(0.0, "left", 300, 150, 350, 150));
    EXPECT_NEAR(app.camera().pose().azimuth, -0.5f, 1e-4f);
    // Right drag up zooms in.
    play(app, 1.0, drag(1.0, "right", 300, 300, 300, 200));
    EXPECT_NEAR(app.camera().pose().distance, home * std::exp(-0.5f), home * 1e-3f);
    // Middle drag pans.
    play(app, 2.0, drag(2.0, "middle", 300, 300, 300, 350));
    EXPECT_GT(glm::length(app.camera().pose().target), 1.0f);
    // Shift+click selects; a plain click does not.
    app.camera().set_pose(CameraPose{{0, 0, 0}, 0.0f, 1.5707964f, home});
    play(app, 3.0, click(3.0, "left", 640, 400));
    EXPECT_EQ(app.selected(), -1);
    play(app, 4.0, click(4.0, "left", 640, 400, "shift"));
    EXPECT_EQ(app.selected(), 1);
    // Shift+drag from the manipulation sphere (at the model's centre) moves it in X-Z.
    play(app, 5.0, drag(5.0, "left", 640, 400, 700, 400, "shift"));
    EXPECT_GT(app.model(1).offset.x, 1.0f);
    EXPECT_NEAR(app.model(1).offset.y, 0.0f, 1e-6f);
    EXPECT_EQ(app.selected(), 1);
    // Shift+drag elsewhere does not move it; Shift+click on empty deselects.
    const glm::vec3 before = app.model(1).offset;
    play(app, 6.0, drag(6.0, "left", 300, 150, 350, 150, "shift") + click(7.0, "left", 300, 150, "shift"));
    EXPECT_EQ(app.model(1).offset, before);
    EXPECT_EQ(app.selected(), -1);
}

TEST(KioskApp, ThesisShiftMiddleButtonMovesInYZAndOnlyDeselects) {
    KioskApp app = make_app();
    app.update(0.0);
    // Shift+middle click on an object does not select it (thesis B.2: only the left button selects).
    play(app, 0.0, click(0.0, "middle", 640, 400, "shift"));
    EXPECT_EQ(app.selected(), -1);
    play(app, 1.0, click(1.0, "left", 640, 400, "shift"));
    ASSERT_EQ(app.selected(), 1);
    // A plain click (no Shift) away from every object leaves the selection alone.
    play(app, 2.0, click(2.0, "left", 300, 150));
    EXPECT_EQ(app.selected(), 1);
    // Shift+middle drag from the manipulation sphere moves the selection in the Y-Z plane:
    // right is +z, down is -y, x stays.
    play(app, 3.0, drag(3.0, "middle", 640, 400, 700, 460, "shift"));
    EXPECT_GT(app.model(1).offset.z, 1.0f);
    EXPECT_LT(app.model(1).offset.y, -1.0f);
    EXPECT_FLOAT_EQ(app.model(1).offset.x, 0.0f);
    EXPECT_EQ(app.model(0).offset, glm::vec3(0.0f));
    // Shift+middle click on another object keeps the selection; away from every object it deselects.
    const float right = screen_x(app, {100, 0, 0});
    ASSERT_EQ(app.pick(right, 400.0f), 2);
    play(app, 4.0, click(4.0, "middle", right, 400, "shift"));
    EXPECT_EQ(app.selected(), 1);
    play(app, 5.0, click(5.0, "middle", 300, 150, "shift"));
    EXPECT_EQ(app.selected(), -1);
}

double simulated_cost(size_t triangles) { return 1.0 + 10.0 * static_cast<double>(triangles) * 1e-6; }

TEST(KioskApp, AutomaticLodHoldsTheFrameTargetAndFavoursTheSelection) {
    KioskApp app = make_app(1000000, 2000);  // full detail 3M triangles = 31 ms simulated
    run_replay(app, replay("0.0 down 1 640 400\n0.1 up 1 640 400\n2.0 end\n"), 60.0, 0.0, simulated_cost);
    ASSERT_EQ(app.selected(), 1);
    const size_t total = app.triangles_planned();
    EXPECT_LE(simulated_cost(total), 16.7);
    EXPECT_GE(simulated_cost(total), 16.7 * 0.8);               // and does not waste the budget
    EXPECT_EQ(app.model(1).triangles, 1000000u);                // the selected model keeps full detail
    EXPECT_GT(app.model(0).triangles, app.model(2).triangles);  // then its group
    EXPECT_GE(app.model(2).triangles, 2000u);                   // never below the base mesh
}

TEST(KioskApp, LodButtonsStepTheSelectionInTenths) {
    KioskApp app = make_app();
    run_replay(app, replay("0.0 down 1 640 400\n0.1 up 1 640 400\n"));
    ASSERT_EQ(app.selected(), 1);
    EXPECT_TRUE(app.lod_auto());
    run_replay(app,
               replay(tap_on(control(app, ControlId::LodDown), 0.5) + tap_on(control(app, ControlId::LodDown), 1.0)),
               60.0, 0.5);
    ASSERT_TRUE(app.model(1).manual_lod);
    EXPECT_FLOAT_EQ(*app.model(1).manual_lod, 0.8f);
    EXPECT_FALSE(app.model(0).manual_lod);
    EXPECT_EQ(app.model(1).triangles, 80000u);
    run_replay(app, replay(tap_on(control(app, ControlId::LodAuto), 1.5)), 60.0, 1.5);
    EXPECT_FALSE(app.model(1).manual_lod);
}

// The glide itself is the model part's (scene/model_part.h, tested with Geomorph).
TEST(KioskApp, LevelChangeTakesTheNewCount) {
    KioskApp app = make_app();
    app.update(0.0);
    app.set_model_lod(0, 0.5f);
    app.update(1.0);
    EXPECT_EQ(app.model(0).triangles, 50000u);
}

TEST(KioskApp, ModelsThatFailedToLoadAreSkipped) {
    auto scene = scene::parse_scene(test::kTestScene, "test.json", "");
    std::vector<ModelInfo> info{
        {true, {-100, 0, 0}, 40, 100, 10}, {false, {}, 1, 0, 0}, {true, {100, 0, 0}, 40, 100, 10}};
    KioskApp app(std::move(scene).value(), std::move(info), 1280, 800);
    app.update(0.0);
    EXPECT_FALSE(app.visible(1));
    EXPECT_EQ(app.pick(640, 400), -1);  // nothing where the missing model would be
    EXPECT_EQ(app.model(1).triangles, 0u);
}

// The platform's events reach the app as they are: a Shift+click from the
// backend selects (thesis B.2), a plain or Ctrl+click does not.
TEST(KioskApp, ShiftClickFromTheBackendSelectsAPlainOneDoesNot) {
    using T = InputEvent::Type;
    KioskApp app = make_app();
    app.update(0.0);
    auto click = [&](double t, uint32_t modifiers) {
        for (T type : {T::MouseDown, T::MouseUp})
            app.handle(platform::test::input_event(type, 0, 640, 400, t, modifiers));
        app.update(t + 0.1);
    };
    click(1.0, 0);
    EXPECT_EQ(app.selected(), -1);
    click(2.0, kModCtrl);
    EXPECT_EQ(app.selected(), -1);
    click(3.0, kModShift);
    EXPECT_EQ(app.selected(), 1);
}

TEST(KioskApp, MouseButtonsAreNumberedAsThePlatformNumbersThem) {
    using T = InputEvent::Type;
    EXPECT_EQ(platform::test::input_event(T::MouseDown, 0, 0, 0, 0).button(), MouseButton::Left);
    EXPECT_EQ(platform::test::input_event(T::MouseDown, 1, 0, 0, 0).button(), MouseButton::Right);
    EXPECT_EQ(platform::test::input_event(T::MouseDown, 2, 0, 0, 0).button(), MouseButton::Middle);
}

}  // namespace
}  // namespace body::kiosk
