// evdev touch mapped into a desktop window (contract in evdev_window.h).
#include "platform/evdev_window.h"

#include <algorithm>

namespace body::platform {

namespace {

bool is_touch(InputEvent::Type t) {
    return t == InputEvent::Type::TouchDown || t == InputEvent::Type::TouchMove || t == InputEvent::Type::TouchUp;
}

// The mouse events X11 pointer emulation produces from a touch (MouseUp is let through).
bool may_be_emulated(InputEvent::Type t) {
    return t == InputEvent::Type::MouseDown || t == InputEvent::Type::MouseMove || t == InputEvent::Type::Scroll;
}

}  // namespace

bool monitor_to_window(const WindowPlacement& w, float monitor_x, float monitor_y, float& x, float& y) {
    const float local_x = monitor_x - static_cast<float>(w.x);
    const float local_y = monitor_y - static_cast<float>(w.y);
    const float scale_x = w.width > 0 ? static_cast<float>(w.framebuffer_width) / static_cast<float>(w.width) : 1.0f;
    const float scale_y = w.height > 0 ? static_cast<float>(w.framebuffer_height) / static_cast<float>(w.height) : 1.0f;
    x = local_x * scale_x;
    y = local_y * scale_y;
    return local_x >= 0.0f && local_y >= 0.0f && local_x < static_cast<float>(w.width) &&
           local_y < static_cast<float>(w.height);
}

bool map_touch_to_window(const TouchMapping& panel, const WindowPlacement& window, int raw_x, int raw_y, float& x,
                         float& y) {
    float monitor_x = 0.0f, monitor_y = 0.0f;
    map_touch(panel, raw_x, raw_y, monitor_x, monitor_y);
    return monitor_to_window(window, monitor_x, monitor_y, x, y);
}

void WindowTouchFilter::apply(std::vector<InputEvent>& events, size_t from) {
    const bool touch_in_batch = std::any_of(events.begin() + static_cast<long>(from), events.end(),
                                            [](const InputEvent& e) { return is_touch(e.type); });
    size_t keep = from;
    for (size_t i = from; i < events.size(); ++i) {
        InputEvent e = events[i];
        if (is_touch(e.type)) {
            last_touch_ = std::max(last_touch_, e.time);
            const bool in = monitor_to_window(window_, e.x, e.y, e.x, e.y);
            if (e.type == InputEvent::Type::TouchDown) {
                (in ? inside_ : outside_).insert(e.id);
                if (!in) continue;
            } else {
                // Contacts that went down outside stay outside; moves of inside
                // ones that leave the window keep their (out-of-range) position.
                const bool was_outside = outside_.count(e.id) > 0;
                const bool was_inside = inside_.count(e.id) > 0;
                if (e.type == InputEvent::Type::TouchUp) {
                    outside_.erase(e.id);
                    inside_.erase(e.id);
                }
                if (was_outside || !was_inside) continue;
            }
        } else if (may_be_emulated(e.type)) {
            const bool touching = touch_in_batch || !inside_.empty() || !outside_.empty() ||
                                  e.time - last_touch_ <= kEmulationGraceSeconds;
            if (touching) continue;
        }
        events[keep++] = e;
    }
    events.resize(keep);
}

}  // namespace body::platform
