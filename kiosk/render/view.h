#pragma once
// What the renderer draws from: one view of the camera, a perspective look-at
// in world units. The camera model that moves is the kiosk's orbit camera
// (kiosk/app/camera.h: OrbitCamera::render_view); a screenshot or the
// benchmark frames the scene directly with framing() / framing_box().
#include "shared/geometry.h"

namespace body::render {

struct View {
    Vec3f eye{0.0f, 0.0f, 3.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
    float fov_y_deg = 35.0f;
    float near_plane = 0.01f, far_plane = 100.0f;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
    // A camera looking at the sphere (center, radius) from `direction` (world,
    // toward the eye) so that it fills the view; near/far hug the sphere.
    static View framing(Vec3f center, float radius, Vec3f direction = {0.35f, 0.25f, 1.0f});
    // A camera looking at the box [lo, hi] from `direction` at the smallest
    // distance where all eight corners fit the view of the given aspect.
    static View framing_box(Vec3f lo, Vec3f hi, Vec3f direction, float aspect, float fov_y_deg = 35.0f);
};

}  // namespace body::render
