// The renderer's view: matrices, and the framings that fit a sphere or a box (contract in view.h).
#include "kiosk/render/view.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace body::render {

glm::mat4 View::view() const { return glm::lookAt(eye, target, up); }
glm::mat4 View::projection(float aspect) const {
    return glm::perspective(glm::radians(fov_y_deg), aspect, near_plane, far_plane);
}
View View::framing(Vec3f center, float radius, Vec3f direction) {
    View c;
    radius = std::max(radius, 1e-6f);
    float d = radius / std::sin(glm::radians(c.fov_y_deg) * 0.5f) * 1.02f;
    c.target = center;
    c.eye = center + glm::normalize(direction) * d;
    c.near_plane = std::max(d - radius * 1.5f, d * 0.01f);
    c.far_plane = d + radius * 1.5f;
    return c;
}

View View::framing_box(Vec3f lo, Vec3f hi, Vec3f direction, float aspect, float fov_y_deg) {
    View c;
    c.fov_y_deg = fov_y_deg;
    c.target = (lo + hi) * 0.5f;
    const Vec3f back = glm::normalize(direction);  // from target toward the eye
    const Vec3f right = glm::normalize(glm::cross(c.up, back));
    const Vec3f up = glm::cross(back, right);
    const float ty = std::tan(glm::radians(fov_y_deg) * 0.5f), tx = ty * aspect;
    float d = 1e-6f, reach = 0.0f;
    for (int i = 0; i < 8; ++i) {
        Vec3f corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        Vec3f o = corner - c.target;
        float toward = glm::dot(o, back);  // positive: nearer to the eye
        d = std::max({d, toward + std::abs(glm::dot(o, right)) / tx, toward + std::abs(glm::dot(o, up)) / ty});
        reach = std::max(reach, glm::length(o));
    }
    d *= 1.04f;
    c.eye = c.target + back * d;
    c.near_plane = std::max(d - reach * 1.05f, d * 0.01f);
    c.far_plane = d + reach * 1.05f;
    return c;
}

}  // namespace body::render
