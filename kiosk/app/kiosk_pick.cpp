// Picking over thousands of models: each model's box (its centre and offset,
// the cube around the sphere that holds its bounds) in a hierarchy (shared/bvh.h),
// walked front to back, so the picker's triangle walk runs only for the models
// whose box the ray enters before the nearest hit found so far.
#include <cmath>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

void KioskApp::refresh_pick_tree() const {
    if (pick_tree_built_ && !pick_tree_stale_) return;
    const size_t n = info_.size();
    pick_lo_.resize(n);
    pick_hi_.resize(n);
    for (size_t i = 0; i < n; ++i) {
        const ModelInfo& m = info_[i];
        // ModelInfo::radius is the bounds' half diagonal over sqrt 3 (scene_models.cpp).
        const float r = m.radius * 1.7320508f * 1.01f;
        const glm::vec3 c = model_center(static_cast<int>(i));
        pick_lo_[i] = m.loaded ? c - r : glm::vec3(1.0f);  // not loaded: an empty box, left out
        pick_hi_[i] = m.loaded ? c + r : glm::vec3(-1.0f);
    }
    if (pick_tree_built_) {
        bvh_refit(pick_tree_, pick_lo_, pick_hi_);  // only offsets change within one app
    } else {
        bvh_build(pick_tree_, pick_lo_, pick_hi_);
    }
    pick_tree_built_ = true;
    pick_tree_stale_ = false;
}

int KioskApp::pick_ray(const Ray& ray, float& distance) const {
    refresh_pick_tree();
    return bvh_nearest(
        pick_tree_, ray,
        [&](uint32_t item) -> std::optional<float> {
            const int i = static_cast<int>(item);
            return visible(i) ? hit_distance(i, ray) : std::nullopt;
        },
        distance);
}

int KioskApp::pick(float x, float y) const {
    float distance = 0.0f;
    return pick_ray(camera_.ray(x, y), distance);
}

}  // namespace body::kiosk
