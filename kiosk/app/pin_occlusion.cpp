// PinOcclusion (pin_occlusion.h): the app's pins to the renderer's queries and back.
#include "kiosk/app/pin_occlusion.h"

namespace body::kiosk {

bool PinOcclusion::init(KioskApp& app) {
    on_ = app.scene().kiosk.pins && queries_.init().ok();
    if (on_) app.take_pin_occlusion_from_renderer();
    return on_;
}

void PinOcclusion::shutdown() {
    queries_.shutdown();
    on_ = false;
}

void PinOcclusion::before_update(KioskApp& app) {
    if (on_ && queries_.collect(false, hidden_)) app.set_pin_occlusion(hidden_, false);
}

void PinOcclusion::after_render(KioskApp& app, const render::View& camera, const render::FrameOptions& frame,
                                bool wait) {
    if (!on_) return;
    points_.clear();
    for (const PinView& p : app.pins()) points_.push_back(Vec3f(app.placement(p.model) * glm::vec4(p.anchor, 1.0f)));
    // Live, a batch still in flight is answered first; a wait answers this frame's.
    if (!queries_.test(camera, frame, points_) || !wait) return;
    if (queries_.collect(true, hidden_)) app.set_pin_occlusion(hidden_, true);
}

}  // namespace body::kiosk
