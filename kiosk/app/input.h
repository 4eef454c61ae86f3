#pragma once
// The kiosk takes the platform's input events as they are (platform/platform.h:
// touch, mouse, Scroll with dy in notches positive away from the user, keys,
// modifiers); replay files (replay.h) produce the same events.
#include "platform/platform.h"

namespace body::kiosk {

using platform::InputEvent;
using platform::kModAlt;
using platform::kModCtrl;
using platform::kModShift;
using platform::MouseButton;

}  // namespace body::kiosk
