#pragma once
// The platform layer's input events (platform/platform.h: glfw mouse and keys,
// evdev touch) as the kiosk's (kiosk/app/input.h): kinds, mouse buttons (the
// platform numbers them 0 left, 1 right, 2 middle), scroll as wheel notches and
// the Shift/Ctrl/Alt modifiers, so Shift+click reaches the gesture layer.
#include <optional>

#include "kiosk/app/input.h"
#include "platform/platform.h"

namespace body::kiosk {

// nullopt for Quit, which is the run loop's business, not the app's.
std::optional<InputEvent> from_platform(const platform::InputEvent& event);

}  // namespace body::kiosk
