// Platform input events to kiosk input events (contract in platform_input.h).
#include "kiosk/app/platform_input.h"

namespace body::kiosk {

namespace {

static_assert(static_cast<uint32_t>(platform::kModShift) == kModShift &&
                  static_cast<uint32_t>(platform::kModCtrl) == kModCtrl &&
                  static_cast<uint32_t>(platform::kModAlt) == kModAlt,
              "platform and kiosk modifier bits differ");

MouseButton button(int platform_id) {
    return platform_id == 1 ? MouseButton::Right : platform_id == 2 ? MouseButton::Middle : MouseButton::Left;
}

}  // namespace

std::optional<InputEvent> from_platform(const platform::InputEvent& e) {
    using T = platform::InputEvent::Type;
    InputEvent k;
    k.time = e.time;
    k.x = e.x;
    k.y = e.y;
    k.id = e.id;
    k.key = e.key;
    k.modifiers = e.modifiers & (kModShift | kModCtrl | kModAlt);
    switch (e.type) {
        case T::TouchDown: k.kind = InputKind::TouchDown; break;
        case T::TouchMove: k.kind = InputKind::TouchMove; break;
        case T::TouchUp: k.kind = InputKind::TouchUp; break;
        case T::MouseDown: k.kind = InputKind::MouseDown; break;
        case T::MouseUp: k.kind = InputKind::MouseUp; break;
        case T::MouseMove: k.kind = InputKind::MouseMove; break;
        case T::Scroll:
            k.kind = InputKind::Wheel;
            k.wheel = e.dy;
            break;
        case T::Key: k.kind = InputKind::Key; break;
        case T::Quit: return std::nullopt;
    }
    if (e.type == T::MouseDown || e.type == T::MouseUp) k.button = button(e.id);
    return k;
}

}  // namespace body::kiosk
