// Touch on a desktop: raw panel coordinates into a window that covers part of
// the touch monitor (placement, HiDPI scale, panel rotation), and the filter
// that keeps contacts which went down inside and drops pointer emulation.
#include "platform/evdev_window.h"

#include <gtest/gtest.h>

#include "tests/platform/input_events.h"

namespace body::platform {
namespace {

// A 1920x1080 monitor; the window's content area at (100, 50), 640x480.
WindowPlacement window(int scale = 1) { return WindowPlacement{100, 50, 640, 480, 640 * scale, 480 * scale}; }

// A panel whose axes span the monitor's pixels exactly when unrotated (so raw =
// monitor pixel); `rotation` swaps the ranges the way a panel mounted turned would have them.
TouchMapping panel(int rotation) {
    const bool turned = rotation == 90 || rotation == 270;
    return TouchMapping{0, turned ? 1079 : 1919, 0, turned ? 1919 : 1079, 1920, 1080, rotation};
}

TEST(EvdevWindow, MapsThePanelIntoTheWindowForEveryRotation) {
    // Each raw point lands on monitor pixel (420, 290): window pixel (320, 240).
    const struct {
        int rotation, raw_x, raw_y;
    } cases[] = {{0, 420, 290}, {90, 290, 1499}, {180, 1499, 789}, {270, 789, 420}};
    for (const auto& c : cases) {
        float x = -1, y = -1;
        EXPECT_TRUE(map_touch_to_window(panel(c.rotation), window(), c.raw_x, c.raw_y, x, y)) << c.rotation;
        EXPECT_NEAR(x, 320.0f, 1e-3f) << c.rotation;
        EXPECT_NEAR(y, 240.0f, 1e-3f) << c.rotation;
    }
}

TEST(EvdevWindow, ScalesToHiDpiFramebuffersAndOffsetRanges) {
    float x = 0, y = 0;
    EXPECT_TRUE(map_touch_to_window(panel(0), window(2), 420, 290, x, y));
    EXPECT_NEAR(x, 640.0f, 1e-3f);
    EXPECT_NEAR(y, 480.0f, 1e-3f);
    // A panel reporting 100..4195 x -50..2109: its middle is the monitor's middle.
    const TouchMapping offset{100, 4195, -50, 2109, 1920, 1080, 0};
    EXPECT_TRUE(map_touch_to_window(offset, WindowPlacement{0, 0, 1920, 1080, 1920, 1080}, 2147, 1029, x, y));
    EXPECT_NEAR(x, 959.5f, 0.5f);
    EXPECT_NEAR(y, 539.5f, 0.5f);
}

TEST(EvdevWindow, PointsOutsideTheWindowAreReported) {
    float x = 0, y = 0;
    EXPECT_FALSE(map_touch_to_window(panel(0), window(), 50, 20, x, y));
    EXPECT_NEAR(x, -50.0f, 1e-3f);  // still written: window coordinates, left of and above the window
    EXPECT_NEAR(y, -30.0f, 1e-3f);
    EXPECT_TRUE(monitor_to_window(window(), 739.0f, 529.0f, x, y));  // the last pixel inside
    EXPECT_FALSE(monitor_to_window(window(), 740.0f, 300.0f, x, y));
    EXPECT_FALSE(monitor_to_window(window(), 300.0f, 530.0f, x, y));
    EXPECT_FALSE(monitor_to_window(window(), 99.5f, 300.0f, x, y));
}

using T = InputEvent::Type;
using test::expect_events;
InputEvent event(T type, int id, float x, float y, double time) { return test::input_event(type, id, x, y, time); }

TEST(EvdevWindow, FilterKeepsContactsThatStartInsideAndMapsThem) {
    WindowTouchFilter filter;
    filter.set_placement(window());
    std::vector<InputEvent> events = {event(T::Key, 0, 0, 0, 0.0),             // before `from`: untouched
                                      event(T::TouchDown, 1, 420, 290, 1.0),   // inside
                                      event(T::TouchDown, 2, 1500, 900, 1.0),  // outside
                                      event(T::TouchMove, 1, 1000, 290, 1.1),  // leaves the window: kept
                                      event(T::TouchMove, 2, 420, 290, 1.1),   // moves in: still dropped
                                      event(T::TouchMove, 7, 420, 290, 1.1)};  // never went down: dropped
    filter.apply(events, 1);
    expect_events(events, {{T::Key, 0, 0.0f, 0.0f}, {T::TouchDown, 1, 320.0f, 240.0f}, {T::TouchMove, 1, 900.0f}});
    EXPECT_EQ(filter.contacts(), 1);

    events = {event(T::TouchUp, 2, 420, 290, 1.2), event(T::TouchUp, 1, 420, 290, 1.2)};
    filter.apply(events, 0);
    expect_events(events, {{T::TouchUp, 1, 320.0f, 240.0f}});
    EXPECT_EQ(filter.contacts(), 0);
    // The ids are free again: a new contact 2 inside is delivered.
    events = {event(T::TouchDown, 2, 420, 290, 3.0)};
    filter.apply(events, 0);
    expect_events(events, {{T::TouchDown, 2}});
}

TEST(EvdevWindow, FilterDropsPointerEmulationAroundTouches) {
    WindowTouchFilter filter;
    filter.set_placement(window());
    // The display server's emulated press arrives in the same poll as the touch.
    std::vector<InputEvent> events = {event(T::MouseDown, 0, 320, 240, 1.0), event(T::TouchDown, 1, 420, 290, 1.0)};
    filter.apply(events, 0);
    expect_events(events, {{T::TouchDown, 1}});
    // While the finger is down: moves dropped, a release always passes.
    events = {event(T::MouseMove, 0, 330, 240, 1.1), event(T::MouseUp, 0, 330, 240, 1.1),
              event(T::TouchUp, 1, 430, 290, 1.1)};
    filter.apply(events, 0);
    expect_events(events, {{T::MouseUp, 0, 330.0f, 240.0f}, {T::TouchUp, 1, 330.0f, 240.0f}});
    // Shortly after the lift: still emulation; later: the real mouse.
    events = {event(T::Scroll, 0, 0, 0, 1.1 + WindowTouchFilter::kEmulationGraceSeconds * 0.5)};
    filter.apply(events, 0);
    EXPECT_TRUE(events.empty());
    events = {event(T::MouseDown, 0, 5, 5, 1.1 + WindowTouchFilter::kEmulationGraceSeconds * 2.0)};
    filter.apply(events, 0);
    EXPECT_EQ(events.size(), 1u);
}

}  // namespace
}  // namespace body::platform
