// The cut plane's controls and gestures, driven by replays: the Cut button's
// cycle, a one-finger drag along the normal, a two-finger tilt, the axis
// presets, a group cut alone, the mouse, and the reset (kiosk/app/cut_plane.h).
#include "kiosk/app/cut_plane.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kiosk/app/kiosk_app.h"
#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

using test::make_app;
using test::replay;

const Control* find(const KioskApp& app, ControlId id) {
    for (const Control& c : app.controls())
        if (c.id == id) return &c;
    return nullptr;
}

std::string line(double t, const std::string& what, int id, float x, float y) {
    return std::to_string(t) + " " + what + " " + std::to_string(id) + " " + std::to_string(x) + " " +
           std::to_string(y) + "\n";
}

// A tap in the middle of control `id` as replay text.
std::string tap(const KioskApp& app, ControlId id, double t) {
    const Control* c = find(app, id);
    EXPECT_TRUE(c != nullptr);
    if (!c) return "";
    const float x = c->rect.x + c->rect.w / 2, y = c->rect.y + c->rect.h / 2;
    return line(t, "down", 9, x, y) + line(t + 0.05, "up", 9, x, y);
}

// One finger from (x, y) moved by (dx, dy) in ten steps.
std::string finger_drag(double t, float x, float y, float dx, float dy) {
    std::string s = line(t, "down", 1, x, y);
    for (int i = 1; i <= 10; ++i)
        s += line(t + 0.02 * i, "move", 1, x + dx * static_cast<float>(i) / 10, y + dy * static_cast<float>(i) / 10);
    return s + line(t + 0.25, "up", 1, x + dx, y + dy);
}

// Two fingers 200 px apart around (x, y), both moved by (dx, dy) in ten steps (a pan without pinch).
std::string two_finger_drag(double t, float x, float y, float dx, float dy) {
    std::string s = line(t, "down", 1, x - 100, y) + line(t, "down", 2, x + 100, y);
    for (int i = 1; i <= 10; ++i) {
        const float f = static_cast<float>(i) / 10;
        s += line(t + 0.02 * i, "move", 1, x - 100 + dx * f, y + dy * f) +
             line(t + 0.02 * i, "move", 2, x + 100 + dx * f, y + dy * f);
    }
    return s + line(t + 0.25, "up", 1, x - 100 + dx, y + dy) + line(t + 0.25, "up", 2, x + 100 + dx, y + dy);
}

void play(KioskApp& app, double t, const std::string& text) { run_replay(app, replay(text), 60.0, t); }

float world_per_px(const KioskApp& app) {
    const OrbitCamera& c = app.camera();
    return 2.0f * c.pose().distance * std::tan(c.fov_y() * 0.5f) / static_cast<float>(c.height());
}

TEST(CutPlane, ButtonCyclesOffMoveFixedOff) {
    KioskApp app = make_app();
    app.update(0.0);
    EXPECT_FALSE(app.cut().on());
    EXPECT_FALSE(app.cut().plane().enabled);
    ASSERT_NE(find(app, ControlId::CutAxis), nullptr);
    EXPECT_FALSE(find(app, ControlId::CutAxis)->enabled);  // no axis to choose while off
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    EXPECT_TRUE(app.cut().on());
    EXPECT_TRUE(app.cut().editing());
    EXPECT_TRUE(app.cut().plane().enabled);
    EXPECT_TRUE(find(app, ControlId::Cut)->active);
    EXPECT_EQ(find(app, ControlId::Cut)->text, "Cut: move");
    EXPECT_EQ(app.cut().axis(), CutAxis::Axial);
    // The axial preset: through the scene's centre, normal +Y (superior) with the eye level with it.
    EXPECT_NEAR(app.cut().normal().y, 1.0f, 1e-6f);
    EXPECT_NEAR(app.cut().offset(), 0.0f, 1e-6f);
    play(app, 0.5, tap(app, ControlId::Cut, 0.5));
    EXPECT_TRUE(app.cut().on());
    EXPECT_FALSE(app.cut().editing());
    EXPECT_EQ(find(app, ControlId::Cut)->text, "Cut: fixed");
    play(app, 1.0, tap(app, ControlId::Cut, 1.0));
    EXPECT_FALSE(app.cut().on());
    EXPECT_EQ(find(app, ControlId::Cut)->text, "Cut: off");
}

TEST(CutPlane, OneFingerDragMovesThePlaneAlongItsNormal) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    const CameraPose before = app.camera().pose();
    const float u = world_per_px(app);
    // Axial, seen from the front: the normal (+Y) points up the screen; 100 px up.
    play(app, 0.5, finger_drag(0.5, 400, 500, 0, -100));
    EXPECT_NEAR(app.cut().offset(), 100.0f * u, 2.0f * u);
    EXPECT_NEAR(app.cut().normal().y, 1.0f, 1e-6f);
    const glm::vec4 p = app.cut().plane().plane;
    EXPECT_NEAR(p.w, -app.cut().offset(), 1e-4f);  // y = offset is the plane (scene centre at 0)
    // The camera did not move: the drag belonged to the plane.
    EXPECT_EQ(app.camera().pose().azimuth, before.azimuth);
    EXPECT_EQ(app.camera().pose().polar, before.polar);
    // Sideways motion does not move it; it stops at the scene's bounding sphere.
    const float at = app.cut().offset();
    play(app, 1.0, finger_drag(1.0, 400, 500, 150, 0));
    EXPECT_NEAR(app.cut().offset(), at, 1e-3f);
    play(app, 1.5, finger_drag(1.5, 400, 700, 0, -600));
    play(app, 2.0, finger_drag(2.0, 400, 700, 0, -600));
    EXPECT_NEAR(app.cut().offset(), 140.0f, 1e-3f);  // the three spheres reach 140 from the centre
}

TEST(CutPlane, PresetsFaceTheEyeAndADragTowardTheEyeMovesItCloser) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    play(app, 0.3, tap(app, ControlId::CutAxis, 0.3));
    EXPECT_EQ(app.cut().axis(), CutAxis::Coronal);
    EXPECT_EQ(find(app, ControlId::CutAxis)->text, "coronal");
    EXPECT_NEAR(app.cut().normal().z, 1.0f, 1e-6f);  // the eye is at +Z
    // The normal faces the eye: dragging up the screen brings the plane toward it.
    play(app, 0.5, finger_drag(0.5, 400, 500, 0, -50));
    EXPECT_NEAR(app.cut().offset(), 50.0f * world_per_px(app), 2.0f * world_per_px(app));
    play(app, 1.0, tap(app, ControlId::CutAxis, 1.0));
    EXPECT_EQ(app.cut().axis(), CutAxis::Sagittal);
    EXPECT_NEAR(std::abs(app.cut().normal().x), 1.0f, 1e-6f);
    EXPECT_NEAR(app.cut().offset(), 0.0f, 1e-6f);  // a preset goes back through the centre
    play(app, 1.5, tap(app, ControlId::CutAxis, 1.5));
    EXPECT_EQ(app.cut().axis(), CutAxis::Axial);
}

TEST(CutPlane, TwoFingersTiltIt) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    const float zoom_before = app.camera().pose().distance;
    const glm::vec3 target_before = app.camera().pose().target;
    // 50 px down with both fingers: the normal turns about the camera's right axis (+X) by 0.25 rad.
    play(app, 0.5, two_finger_drag(0.5, 640, 400, 0, 50));
    const float a = 50.0f * CutPlane::kTiltRadiansPerPixel;
    EXPECT_NEAR(app.cut().normal().y, std::cos(a), 1e-3f);
    EXPECT_NEAR(std::abs(app.cut().normal().z), std::sin(a), 1e-3f);
    EXPECT_NEAR(app.cut().normal().x, 0.0f, 1e-5f);
    EXPECT_NEAR(glm::length(app.cut().normal()), 1.0f, 1e-5f);
    // The camera neither panned nor zoomed.
    EXPECT_FLOAT_EQ(app.camera().pose().distance, zoom_before);
    EXPECT_FLOAT_EQ(app.camera().pose().target.x, target_before.x);
    EXPECT_FLOAT_EQ(app.camera().pose().target.y, target_before.y);
    // Sideways turns it about the camera's up axis (+Y): x gains, y stays.
    const float y_before = app.cut().normal().y;
    play(app, 1.0, two_finger_drag(1.0, 640, 400, 60, 0));
    EXPECT_GT(std::abs(app.cut().normal().x), 0.05f);
    EXPECT_NEAR(app.cut().normal().y, y_before, 1e-3f);
}

TEST(CutPlane, FixedPlaneLetsGesturesMoveTheCamera) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1) + tap(app, ControlId::Cut, 0.3));
    ASSERT_TRUE(app.cut().on() && !app.cut().editing());
    const float az = app.camera().pose().azimuth;
    play(app, 0.6, finger_drag(0.6, 400, 500, 120, -100));
    EXPECT_NE(app.camera().pose().azimuth, az);
    EXPECT_NEAR(app.cut().offset(), 0.0f, 1e-6f);
}

TEST(CutPlane, MouseDragsMoveAndTiltIt) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    play(app, 0.5, "0.5 mouse-down left 400 500\n0.6 mouse-move 400 440\n0.7 mouse-up left 400 440\n");
    EXPECT_NEAR(app.cut().offset(), 60.0f * world_per_px(app), 2.0f * world_per_px(app));
    play(app, 1.0, "1.0 mouse-down middle 400 500\n1.1 mouse-move 400 540\n1.2 mouse-up middle 400 540\n");
    EXPECT_NEAR(app.cut().normal().y, std::cos(40.0f * CutPlane::kTiltRadiansPerPixel), 1e-3f);
}

TEST(CutPlane, AGroupIsCutAloneWhenItsModelIsSelected) {
    KioskApp app = make_app();
    app.update(0.0);
    app.select(2);  // "right", group cortex
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    EXPECT_FALSE(app.cut_applies(0));
    EXPECT_FALSE(app.cut_applies(1));
    EXPECT_TRUE(app.cut_applies(2));
    play(app, 0.5, tap(app, ControlId::Cut, 0.5) + tap(app, ControlId::Cut, 0.7));
    app.select(-1);
    play(app, 1.0, tap(app, ControlId::Cut, 1.0));
    for (int i = 0; i < 3; ++i) EXPECT_TRUE(app.cut_applies(i));
}

TEST(CutPlane, ResetTurnsItOff) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1) + tap(app, ControlId::CutAxis, 0.3));
    ASSERT_TRUE(app.cut().on());
    play(app, 0.5, "12.0 end\n");  // past kiosk.reset_seconds (10)
    EXPECT_FALSE(app.cut().on());
    EXPECT_EQ(app.cut().axis(), CutAxis::Axial);
}

TEST(CutPlane, SceneAxesOverrideThePresets) {
    auto scene = scene::parse_scene(R"({"models": [{"name": "a", "file": "a.obj"}],
        "cut_plane": {"axial": [0, 0, 2], "sagittal": [0, -1, 0]}})",
                                    "cut.json", "");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    KioskApp app(std::move(scene).value(), {ModelInfo{true, {0, 0, 0}, 40.0f, 1000, 100}}, 1280, 800);
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    EXPECT_NEAR(app.cut().normal().z, 1.0f, 1e-6f);  // axial = +Z here, unit, toward the eye
    play(app, 0.3, tap(app, ControlId::CutAxis, 0.3));
    EXPECT_NEAR(app.cut().normal().z, 1.0f, 1e-6f);  // coronal keeps its default +Z
    play(app, 0.5, tap(app, ControlId::CutAxis, 0.5));
    EXPECT_NEAR(std::abs(app.cut().normal().y), 1.0f, 1e-6f);
    for (const char* bad : {R"("cut_plane": {"axial": [0, 0, 0]})", R"("cut_plane": {"oblique": [1, 0, 0]})",
                            R"("cut_plane": {"coronal": [1, 0]})"}) {
        auto r = scene::parse_scene(std::string(R"({"models": [{"name": "a", "file": "a.obj"}], )") + bad + "}",
                                    "cut.json", "");
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("cut.json: cut_plane."), std::string::npos) << r.error().message;
    }
}

}  // namespace
}  // namespace body::kiosk

namespace body::kiosk {
namespace {

// The kiosk's test scene with input slices on planes y = at[i] (cut_plane.slices).
KioskApp app_with_slices(const std::vector<float>& at) {
    auto scene = scene::parse_scene(test::kTestScene, "test.json", "");
    EXPECT_TRUE(scene);
    scene->cut_plane.slices = at;
    std::vector<ModelInfo> info;
    for (float x : {-100.0f, 0.0f, 100.0f}) info.push_back(ModelInfo{true, {x, 0, 0}, 40.0f, 100000, 1000});
    return KioskApp(std::move(scene).value(), std::move(info), 1280, 800);
}

}  // namespace

// Near an input slice the dragged plane lies exactly on it; dragging on past
// kSnapPixels leaves it; a tilt within kSnapDegrees stays on it.
TEST(CutPlane, SnapsToInputSlicesWithinTheTolerance) {
    const float u = [] {
        KioskApp probe = make_app();
        probe.update(0.0);
        return world_per_px(probe);
    }();
    const float tol = CutPlane::kSnapPixels;
    KioskApp app = app_with_slices({40.0f * u, 100.0f * u});
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    EXPECT_EQ(app.cut().snapped_slice(), -1);
    // 33 px up: 7 px from the slice at 40 px, within the tolerance: exactly on it.
    play(app, 0.5, finger_drag(0.5, 400, 500, 0, -33));
    EXPECT_EQ(app.cut().snapped_slice(), 0);
    EXPECT_EQ(app.cut().normal(), glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(app.cut().offset(), 40.0f * u);
    EXPECT_FLOAT_EQ(app.cut().plane().plane.w, -40.0f * u);
    // 10 px further: the fingers are 3 px past it, still on it.
    play(app, 1.0, finger_drag(1.0, 400, 500, 0, -10));
    EXPECT_EQ(app.cut().snapped_slice(), 0);
    EXPECT_FLOAT_EQ(app.cut().offset(), 40.0f * u);
    // 20 px further (each drag loses a few pixels to the touch slop): beyond the
    // tolerance of both slices, the plane follows the fingers.
    play(app, 1.5, finger_drag(1.5, 400, 500, 0, -20));
    EXPECT_EQ(app.cut().snapped_slice(), -1);
    EXPECT_GT(app.cut().offset(), (40.0f + tol) * u);
    EXPECT_LT(app.cut().offset(), (100.0f - tol) * u);
    // Up to the second slice, then a tilt of 3 px (0.86 degrees): still on it, normal and all.
    play(app, 2.0, finger_drag(2.0, 400, 500, 0, -45));
    EXPECT_EQ(app.cut().snapped_slice(), 1);
    play(app, 2.5, two_finger_drag(2.5, 640, 400, 0, 3));
    EXPECT_EQ(app.cut().snapped_slice(), 1);
    EXPECT_EQ(app.cut().normal(), glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_FLOAT_EQ(app.cut().offset(), 100.0f * u);
    // Tilted on past kSnapDegrees: off the slice.
    play(app, 3.0, two_finger_drag(3.0, 640, 400, 0, 20));
    EXPECT_EQ(app.cut().snapped_slice(), -1);
    EXPECT_LT(app.cut().normal().y, std::cos(glm::radians(CutPlane::kSnapDegrees)));
}

TEST(CutPlane, NoSlicesNoSnapping) {
    KioskApp app = make_app();
    app.update(0.0);
    play(app, 0.1, tap(app, ControlId::Cut, 0.1));
    play(app, 0.5, finger_drag(0.5, 400, 500, 0, -33));
    EXPECT_EQ(app.cut().snapped_slice(), -1);
    EXPECT_NEAR(app.cut().offset(), 33.0f * world_per_px(app), 2.0f * world_per_px(app));
}

}  // namespace body::kiosk

namespace body::kiosk {

TEST(CutPlane, BadSlicesNameThePlace) {
    const std::pair<const char*, const char*> cases[] = {
        {R"({"models": [{"name": "a", "file": "a.obj"}], "cut_plane": {"slices": [1, "x"]}})",
         "s.json: cut_plane.slices[1]: "},
        {R"({"models": [{"name": "a", "file": "a.obj"}], "cut_plane": {"slices": 3}})", "s.json: cut_plane.slices: "},
        {R"({"models": [{"name": "a", "file": "a.obj"}], "cut_plane": {"slice_normal": [0, 0, 0]}})",
         "s.json: cut_plane.slice_normal: expected a non-zero direction"},
        {R"({"models": [{"name": "a", "file": "a.obj"}], "cut_plane": {"volume_around": "yes"}})",
         "s.json: cut_plane.volume_around: expected true or false"},
    };
    for (const auto& [text, prefix] : cases) {
        auto s = scene::parse_scene(text, "s.json", "");
        ASSERT_FALSE(s) << text;
        EXPECT_EQ(s.error().message.rfind(prefix, 0), 0u) << s.error().message;
    }
}

}  // namespace body::kiosk
