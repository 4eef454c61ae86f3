// The operator mode behind the admin gesture (kiosk/app/operator_mode.h),
// replayed through KioskApp: the keypad, wrong and right PINs, the
// diagnostics panel, restart and close, and the gesture exiting at once when
// the manifest sets no PIN.
#include <gtest/gtest.h>

#include "kiosk/app/kiosk_app.h"
#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

using test::replay;

KioskApp make(const std::string& kiosk) {
    auto scene =
        scene::parse_scene(R"({"models": [{"name": "a", "file": "a.obj"}], "kiosk": )" + kiosk + "}", "op.json", "");
    EXPECT_TRUE(scene) << scene.error().message;
    return KioskApp(std::move(scene).value(), {ModelInfo{true, {0, 0, 0}, 40.0f, 1000, 100}}, 1280, 800);
}

// Five taps in the top-left corner, 0.2 s apart, from `t`.
std::string admin(double t) {
    std::string s;
    for (int i = 0; i < 5; ++i) {
        const double at = t + 0.2 * i;
        s += std::to_string(at) + " down 1 10 10\n" + std::to_string(at + 0.05) + " up 1 10 10\n";
    }
    return s;
}

const Control* find(const KioskApp& app, ControlId id, int group = -1) {
    for (const Control& c : app.controls()) {
        if (c.id == id && (group < 0 || c.group == group)) return &c;
    }
    return nullptr;
}

// Taps on the keypad keys in `keys` (0-9, OperatorMode::kOk, kCancel), 0.1 s apart from `t`.
void keys(KioskApp& app, double t, std::initializer_list<int> ks) {
    for (int k : ks) {
        const Control* c = find(app, ControlId::OperatorKey, k);
        ASSERT_NE(c, nullptr) << k;
        const float x = c->rect.x + c->rect.w / 2, y = c->rect.y + c->rect.h / 2;
        run_replay(app,
                   replay(std::to_string(t) + " down 2 " + std::to_string(x) + " " + std::to_string(y) + "\n" +
                          std::to_string(t + 0.03) + " up 2 " + std::to_string(x) + " " + std::to_string(y) + "\n"),
                   60.0, t);
        t += 0.1;
    }
}

TEST(OperatorMode, PinOpensTheDiagnosticsAndRestartExits) {
    KioskApp app = make(R"({"operator_pin": "2718"})");
    run_replay(app, replay(admin(0.1)));
    EXPECT_FALSE(app.exit_requested());
    ASSERT_EQ(app.operator_mode().state(), OperatorMode::State::Pin);
    EXPECT_EQ(find(app, ControlId::Home), nullptr);  // modal: only the keypad
    // A drag on the scene does nothing while the keypad is up.
    const float azimuth = app.camera().pose().azimuth;
    run_replay(app, replay("1.5 down 3 200 600\n1.6 move 3 400 600\n1.7 up 3 400 600\n"), 60.0, 1.5);
    EXPECT_EQ(app.camera().pose().azimuth, azimuth);
    // A wrong PIN clears the entry; the right one opens the panel.
    keys(app, 2.0, {2, 7, 1, 9, OperatorMode::kOk});
    EXPECT_EQ(app.operator_mode().state(), OperatorMode::State::Pin);
    EXPECT_EQ(app.operator_mode().entered(), "");
    keys(app, 3.0, {2, 7, 1});
    EXPECT_EQ(find(app, ControlId::OperatorInfo)->text, "PIN ***");
    keys(app, 3.5, {8, OperatorMode::kOk});
    ASSERT_EQ(app.operator_mode().state(), OperatorMode::State::Open);
    app.report_frame(20.0, 5000);
    app.report_frame(30.0, 6000);
    run_replay(app, replay("60.0 end\n"), 60.0, 4.0);
    std::vector<std::string> info;
    for (const Control& c : app.controls())
        if (c.id == ControlId::OperatorInfo) info.push_back(c.text);
    ASSERT_EQ(info.size(), 4u);
    EXPECT_EQ(info[0], "Frame 25.0 ms");
    EXPECT_EQ(info[1], "6000 triangles, LOD auto");
    EXPECT_NE(info[2].find("MiB"), std::string::npos);
    EXPECT_EQ(info[3], "Uptime 0h 01m 00s");
    // Restart: the kiosk exits (its service starts it again).
    const Control* restart = find(app, ControlId::OperatorRestart);
    ASSERT_NE(restart, nullptr);
    const float x = restart->rect.x + 5, y = restart->rect.y + 5;
    run_replay(app,
               replay("60.1 down 2 " + std::to_string(x) + " " + std::to_string(y) + "\n60.15 up 2 " +
                      std::to_string(x) + " " + std::to_string(y) + "\n"),
               60.0, 60.1);
    EXPECT_TRUE(app.exit_requested());
}

TEST(OperatorMode, CancelCloseAndThreeWrongPinsGiveTheKioskBack) {
    KioskApp app = make(R"({"operator_pin": "1234"})");
    run_replay(app, replay(admin(0.1)));
    keys(app, 1.5, {OperatorMode::kCancel});
    EXPECT_FALSE(app.operator_mode().active());
    EXPECT_NE(find(app, ControlId::Home), nullptr);
    run_replay(app, replay(admin(2.0)), 60.0, 2.0);
    keys(app, 3.5, {9, OperatorMode::kOk, 9, OperatorMode::kOk});
    EXPECT_TRUE(app.operator_mode().active());
    keys(app, 4.0, {9, OperatorMode::kOk});
    EXPECT_FALSE(app.operator_mode().active());
    run_replay(app, replay(admin(5.0)), 60.0, 5.0);
    keys(app, 6.5, {1, 2, 3, 4, OperatorMode::kOk});
    ASSERT_EQ(app.operator_mode().state(), OperatorMode::State::Open);
    const Control* close = find(app, ControlId::OperatorClose);
    ASSERT_NE(close, nullptr);
    const float x = close->rect.x + 5, y = close->rect.y + 5;
    run_replay(app,
               replay("7.5 down 2 " + std::to_string(x) + " " + std::to_string(y) + "\n7.55 up 2 " + std::to_string(x) +
                      " " + std::to_string(y) + "\n"),
               60.0, 7.5);
    EXPECT_FALSE(app.operator_mode().active());
    EXPECT_FALSE(app.exit_requested());
}

TEST(OperatorMode, WithoutAPinTheGestureExitsAndBadPinsAreErrors) {
    KioskApp app = make("{}");
    run_replay(app, replay(admin(0.1)));
    EXPECT_TRUE(app.exit_requested());
    for (const char* bad : {R"({"operator_pin": "12a4"})", R"({"operator_pin": "123"})", R"({"operator_pin": 1234})"}) {
        auto s = scene::parse_scene(
            R"({"models": [{"name": "a", "file": "a.obj"}], "kiosk": )" + std::string(bad) + "}", "op.json", "");
        ASSERT_FALSE(s) << bad;
        EXPECT_EQ(s.error().message, "op.json: kiosk.operator_pin: expected a string of 4 to 12 digits");
    }
}

}  // namespace
}  // namespace body::kiosk
