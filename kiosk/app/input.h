#pragma once
// The kiosk's input events, independent of where they come from (evdev touch,
// GLFW mouse, a replay file). Positions are screen pixels, origin top-left, y
// down; time is seconds on the caller's monotonic clock.
#include <cstdint>

namespace body::kiosk {

enum class InputKind : uint8_t { TouchDown, TouchMove, TouchUp, MouseDown, MouseMove, MouseUp, Wheel, Key };
enum class MouseButton : uint8_t { Left, Middle, Right };
enum Modifier : uint32_t { kModShift = 1, kModCtrl = 2, kModAlt = 4 };

struct InputEvent {
    InputKind kind = InputKind::TouchMove;
    double time = 0.0;
    int id = 0;  // touch contact id (unique while the finger is down)
    float x = 0.0f, y = 0.0f;
    MouseButton button = MouseButton::Left;
    uint32_t modifiers = 0;
    float wheel = 0.0f;  // notches, positive away from the user (zoom in)
    int key = 0;         // platform key code (unused by the kiosk except the admin build's Escape)
};

}  // namespace body::kiosk
