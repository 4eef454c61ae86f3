#pragma once
// The kiosk loop: loads a scene through SceneModels (a model that fails to load
// is skipped with a logged reason), then per frame feeds input (the surface's
// events, touch included, or a replay file on a fixed 60 Hz clock) to KioskApp,
// binds its state (styles, visibility, selection, moved objects, the LOD the
// automatic controller chose) to the scene's models, draws the frame with the
// controls and label card over it and presents.
//
// Faults: GL_OUT_OF_MEMORY halves the detail cap (every model's LOD ratio is
// multiplied by it, down to 1/16) with a log line, and the kiosk goes on; a
// context lost to a GPU reset ends the loop with exit 1 and a log line, so the
// service manager starts a fresh process (a new context) at once.
//
// Exit: the admin gesture, the platform's quit (SIGTERM, window closed), the
// end of a replay, `frames`, a lost context, or a hook's stop. Visitors have no
// other way out.
#include <functional>
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "kiosk/scene/scene_models.h"
#include "platform/gl_health.h"
#include "platform/platform.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

class KioskApp;
struct Replay;

// What one presented frame was, for the hooks.
struct FrameReport {
    long frame = 0;         // 0 for the first frame
    double now = 0.0;       // the app's clock at the frame (seconds)
    double frame_ms = 0.0;  // wall time from the frame's start to after present()
    size_t triangles = 0;   // drawn
    const KioskApp* app = nullptr;
    int gl_errors = 0;           // glGetError values raised during the frame (the loop reads them, once)
    bool out_of_memory = false;  // one was GL_OUT_OF_MEMORY: detail has been lowered
    size_t shaped_lines = 0;     // text lines the overlay has shaped so far (Overlay::shaped_lines)
    size_t models_pending = 0;   // models whose base meshes had not arrived when the frame was drawn
    long heap_given_back = 0;    // idle give-backs of the heap so far (IdleMemory::given_back), this frame's included
};

// Optional callbacks into the one loop (the soak's visitors, the service's
// notifications). Called on the loop's thread with the GL context current.
struct KioskHooks {
    // Appends this frame's extra input (after the surface's, before the app sees them).
    std::function<void(const KioskApp& app, double now, std::vector<platform::InputEvent>& events)> input;
    // After each presented frame; returning false ends the loop (exit code unchanged).
    std::function<bool(const FrameReport& report)> frame_done;
    // Reads the context's errors and reset status after each frame; empty:
    // platform::read_gl_health (tests put faults in here).
    std::function<platform::GlHealth()> gl_health;
};

struct KioskRunOptions {
    std::string replay;  // replay file; empty: live input
    // A replay already read (the authoring mode's preview in its own replays);
    // used when `replay` is empty.
    const Replay* replay_events = nullptr;
    std::string screenshot;  // PNG of the last frame (replay end, or `frames`)
    long frames = 0;         // > 0: stop after this many frames
    bool auto_lod = true;    // false: every model at its manifest LOD (benchmarks: controller off)
    std::string font = {};   // empty: the build's BODY_FONT_FILE
    bool verbose = false;    // time to first frame / full detail and frame statistics on stderr
    // Report measured frame times to the LOD controller. Off for replays by default
    // so that a replay's screenshot does not depend on the machine's speed.
    bool measure_frames_in_replay = false;
    render::RendererOptions renderer = {};  // --buffer-access
    LoadOptions load = {};                  // file colours for a model shown alone
    // Every model's base mesh before the first frame even when live (a replay
    // or a screenshot always waits so); false: the first frame draws what has
    // arrived and the rest are uploaded over the next frames.
    bool load_all_first = false;
    KioskHooks hooks = {};
    double display_width_mm = 0.0;  // > 0: overrides the display's reported size (touch targets)
};

// Returns a process exit code (0 ok, 1 runtime failure, 2 bad input).
int run_kiosk(platform::Surface& surface, const scene::Scene& scene, const KioskRunOptions& options);

}  // namespace body::kiosk
