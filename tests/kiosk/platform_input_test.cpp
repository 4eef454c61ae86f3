// Platform events (what the glfw backend delivers) reaching the kiosk: kinds,
// buttons and modifiers convert, and a Shift+click from the backend selects.
#include "kiosk/app/platform_input.h"

#include <gtest/gtest.h>

#include "kiosk_test_scene.h"
#include "tests/platform/input_events.h"

namespace body::kiosk {
namespace {

// Platform events; for mouse events the id is the button (0 left, 1 right, 2 middle).
using platform::test::input_event;

TEST(PlatformInput, ConvertsKindsButtonsAndModifiers) {
    using T = platform::InputEvent::Type;
    auto down = from_platform(input_event(T::MouseDown, 2, 5, 6, 0.5, platform::kModShift | platform::kModAlt));
    ASSERT_TRUE(down);
    EXPECT_EQ(down->kind, InputKind::MouseDown);
    EXPECT_EQ(down->button, MouseButton::Middle);
    EXPECT_EQ(down->modifiers, kModShift | kModAlt);
    EXPECT_FLOAT_EQ(down->x, 5.0f);
    EXPECT_DOUBLE_EQ(down->time, 0.5);
    EXPECT_EQ(from_platform(input_event(T::MouseUp, 1, 0, 0, 0, 0))->button, MouseButton::Right);
    EXPECT_EQ(from_platform(input_event(T::MouseUp, 0, 0, 0, 0, platform::kModCtrl))->modifiers, kModCtrl);
    platform::InputEvent scroll = input_event(T::Scroll, 0, 1, 2, 0, 0);
    scroll.dy = -2.0f;
    EXPECT_EQ(from_platform(scroll)->kind, InputKind::Wheel);
    EXPECT_FLOAT_EQ(from_platform(scroll)->wheel, -2.0f);
    platform::InputEvent touch = input_event(T::TouchMove, 65537, 3, 4, 0, 0);
    EXPECT_EQ(from_platform(touch)->kind, InputKind::TouchMove);
    EXPECT_EQ(from_platform(touch)->id, 65537);
    EXPECT_FALSE(from_platform(input_event(T::Quit, 0, 0, 0, 0, 0)));
}

TEST(PlatformInput, ShiftClickFromTheBackendSelectsAPlainOneDoesNot) {
    using T = platform::InputEvent::Type;
    KioskApp app = test::make_app();
    app.update(0.0);
    auto click = [&](double t, uint32_t modifiers) {
        for (T type : {T::MouseDown, T::MouseUp})
            app.handle(*from_platform(input_event(type, 0, 640, 400, t, modifiers)));
        app.update(t + 0.1);
    };
    click(1.0, 0);
    EXPECT_EQ(app.selected(), -1);
    click(2.0, platform::kModCtrl);
    EXPECT_EQ(app.selected(), -1);
    click(3.0, platform::kModShift);
    EXPECT_EQ(app.selected(), 1);
}

}  // namespace
}  // namespace body::kiosk
