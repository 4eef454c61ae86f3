#pragma once
// `bodyview --author`: the authoring window. The 3-D view is the kiosk's own
// path (scene/scene_models.h to the renderer, app/kiosk_app.h for the camera,
// picking, selection and the manipulation sphere); the editor (editor.h) and
// its side panel (panel_draw.h) sit over it. Preview runs the kiosk loop itself
// (app/kiosk_run.h) on the document's scene, so it is exactly what visitors
// get; Esc (or P) comes back.
//
// Edits apply in the next frame: styles, LOD, visibility, transforms and
// colours are bound to the loaded models; an added or removed model is
// uploaded or dropped alone (SceneModels::insert_model / erase_model); only a
// changed file reloads every model.
//
// The 3-D view's mouse: click selects (and marks the point for Add pin);
// left drag orbits, right drag pans, wheel zooms; on the selected model's
// manipulation sphere Shift+drag moves, Alt+drag rotates (arcball), Alt+Shift+
// drag scales (manipulation.h), Ctrl or the snap toggle snaps; a drag on a pin's
// marker moves the pin along its model's surface. Each is one undoable command.
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "platform/platform.h"
#include "shared/error.h"
#include "shared/scene/scene.h"

namespace body::kiosk::author {

// What the command line opens: the scene and where Ctrl+S writes it.
struct AuthorStart {
    scene::Scene scene;
    std::string path;  // scene.json to save to
};

// `inputs`: BUNDLE/ (its scene.json, or a new one there when models follow),
// scene.json, and/or model files (.bpm, .obj; .stl and .ply are converted into
// the scene's models/ folder) added to the scene. Models alone make a new
// scene saved as ./scene.json.
Result<AuthorStart> open_for_authoring(const std::vector<std::string>& inputs);

struct AuthorRunOptions {
    std::string replay;              // replay file (kiosk/app/replay.h); empty: live input
    std::string screenshot;          // PNG of the author's last frame
    std::string preview_screenshot;  // PNG of a preview's last frame (in a replay: the preview lasts kPreviewSeconds)
    long frames = 0;                 // > 0: stop after this many frames
    std::string font;                // empty: the build's font
    // --kiosk-stats: on stderr, how long loading every model took and, per edit, how long
    // applying it to the view took, how (rebound, one model uploaded or dropped, all
    // reloaded) and the wall time of the frame that drew it.
    bool stats = false;
    render::RendererOptions renderer;
};

// A preview inside a replay runs the kiosk for this long on its 60 Hz clock.
inline constexpr double kPreviewSeconds = 0.5;

// Returns a process exit code.
int run_author(platform::Surface& surface, const AuthorStart& start, const AuthorRunOptions& options);

}  // namespace body::kiosk::author
