#pragma once
// The kiosk loop: loads a scene into the renderer (a model that fails to load
// is skipped with a logged reason), then per frame feeds input (the surface's
// events, or a replay file on a fixed 60 Hz clock) to KioskApp, applies its
// state (camera, styles, visibility, selection, moved objects, LOD chosen by
// the automatic controller) to the renderer, draws the controls and label card
// over the frame and presents. Tap-select picks with CPU ray-triangle tests
// against each model's current level.
//
// Exit: the admin gesture, the platform's quit (SIGTERM, window closed), the
// end of a replay, or `frames`. Visitors have no other way out.
#include <glm/glm.hpp>
#include <string>

#include "kiosk/render/renderer.h"
#include "platform/platform.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

struct KioskRunOptions {
    std::string replay;      // replay file; empty: live input
    std::string screenshot;  // PNG of the last frame (replay end, or `frames`)
    long frames = 0;         // > 0: stop after this many frames
    bool auto_lod = true;    // false: every model at its manifest LOD (benchmarks: controller off)
    std::string font = {};   // empty: the build's BODY_FONT_FILE
    bool verbose = false;    // time to first frame / full detail and frame statistics on stderr
    // Report measured frame times to the LOD controller. Off for replays by default
    // so that a replay's screenshot does not depend on the machine's speed.
    bool measure_frames_in_replay = false;
    // DRM backend: touch screens from /dev/input (platform/evdev_input.h), with the
    // panel turned this many degrees clockwise relative to the picture.
    int touch_rotation = 0;
    render::RendererOptions renderer = {};  // --buffer-access
};

// A scene style as the renderer's style, and a scene transform as a model matrix
// (translate * Rz * Ry * Rx * scale: Euler X first, as SCENE.md says).
render::Style to_render_style(scene::Style style);
glm::mat4 to_model_matrix(const scene::Transform& transform);

// Returns a process exit code (0 ok, 1 runtime failure, 2 bad input).
int run_kiosk(platform::Surface& surface, const scene::Scene& scene, const KioskRunOptions& options);

}  // namespace body::kiosk
