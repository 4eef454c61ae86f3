#pragma once
// The pins' occlusion by the renderer's depth buffer, between a KioskApp and
// render::PointOcclusion: the kiosk loop and the benchmark call it around
// each frame. Each frame after drawing, the pins' anchors (where the app
// placed them) are queried against the depth buffer; the answers reach the
// app as soon as they are ready, a frame or more later, without stalling (the
// app's pins then follow the camera by that much), or at once when `wait` (a
// replay or a screenshot: its frame shows its own answers, whatever the
// machine's speed). The cost per frame is one one-pixel draw per pin,
// whatever the models' size; the app's CPU ray test is left to loops without
// a renderer (the GL-free tests).
#include <vector>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/render/point_occlusion.h"

namespace body::kiosk {

class PinOcclusion {
public:
    // False when the scene has no pins or the queries cannot run: the app then
    // keeps its own ray test. A GLES 3.0 context must be current.
    bool init(KioskApp& app);
    void shutdown();
    // Before app.update(): hands over the answers of an earlier frame, when ready.
    void before_update(KioskApp& app);
    // After Renderer::render(camera, ..., frame), before the overlay.
    void after_render(KioskApp& app, const render::View& camera, const render::FrameOptions& frame, bool wait);

private:
    render::PointOcclusion queries_;
    bool on_ = false;
    std::vector<Vec3f> points_;
    std::vector<char> hidden_;
};

}  // namespace body::kiosk
