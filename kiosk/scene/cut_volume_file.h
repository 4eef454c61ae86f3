#pragma once
// The scene's grey-level volume (scene.json cut_plane.volume) read and handed
// to the renderer for the cut plane's caps (kiosk/render/cut_volume.h), by
// SceneModels::load. A missing or bad file is one log line
// ("bodyview: cut plane volume skipped: PATH: reason") and plain caps.
#include "kiosk/render/renderer.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

// True when the scene names a volume and the renderer took it.
bool load_cut_volume(const scene::Scene& scene, render::Renderer& renderer);

}  // namespace body::kiosk
