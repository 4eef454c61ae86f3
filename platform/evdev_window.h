#pragma once
// Touchscreens on a desktop: evdev touch (platform/evdev_touch.h) delivered into
// a window that covers only part of the touch monitor. GLFW 3.3 has no touch
// API, so the glfw backend reads the panels itself and passes their contacts
// through these pure functions.
//
// Spaces:
//   - monitor: the touch monitor in screen coordinates, origin its top-left;
//     evdev devices are opened with the monitor's size, so map_touch() (with the
//     panel's rotation) lands here;
//   - window: the window's framebuffer pixels, origin top-left. The content area
//     sits at (x, y) on the monitor with size width x height (screen
//     coordinates); framebuffer pixels may be denser (HiDPI).
//
// WindowTouchFilter also drops the mouse events a display server synthesises
// from the same touches (X11 pointer emulation), which would otherwise act
// twice: while a contact is down and for `emulation_grace_s` after the last one
// lifts, MouseDown/MouseMove/Scroll are dropped (MouseUp always passes, so no
// button stays held).
#include <set>
#include <vector>

#include "platform/evdev_touch.h"
#include "platform/platform.h"

namespace body::platform {

struct WindowPlacement {
    int x = 0, y = 0;                                   // content area's top-left on the monitor
    int width = 0, height = 0;                          // content area, screen coordinates
    int framebuffer_width = 0, framebuffer_height = 0;  // pixels
};

// A point in monitor coordinates to window pixels. Returns false (x, y still
// written) when the point lies outside the window's content area.
bool monitor_to_window(const WindowPlacement& window, float monitor_x, float monitor_y, float& x, float& y);

// Raw panel coordinates to window pixels: map_touch() onto the monitor
// (`panel.width/height` = the monitor's size, `panel.rotation`), then
// monitor_to_window(). Returns false when the touch lies outside the window.
bool map_touch_to_window(const TouchMapping& panel, const WindowPlacement& window, int raw_x, int raw_y, float& x,
                         float& y);

class WindowTouchFilter {
public:
    static constexpr double kEmulationGraceSeconds = 0.5;

    void set_placement(const WindowPlacement& window) { window_ = window; }
    // Rewrites events[from..] in place. Touch events arrive in monitor
    // coordinates and leave in window pixels; a contact that goes down outside
    // the window is dropped with all its later events; pointer-emulation mouse
    // events are dropped as described above.
    void apply(std::vector<InputEvent>& events, size_t from);
    int contacts() const { return static_cast<int>(inside_.size()); }

private:
    WindowPlacement window_;
    std::set<int> inside_, outside_;  // contact ids down inside / outside the window
    double last_touch_ = -1e9;
};

}  // namespace body::platform
