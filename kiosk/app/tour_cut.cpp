// A tour's cut plane between steps (contract in tour_cut.h).
#include "kiosk/app/tour_cut.h"

#include <algorithm>
#include <cmath>

namespace body::kiosk {

glm::vec3 turn_normal(glm::vec3 a, glm::vec3 b, float t) {
    t = std::clamp(t, 0.0f, 1.0f);
    const float c = std::clamp(glm::dot(a, b), -1.0f, 1.0f);
    if (c > 0.9995f) return glm::normalize(a + (b - a) * t);  // nearly the same: a straight blend is exact enough
    glm::vec3 axis = glm::cross(a, b);
    if (glm::length(axis) < 1e-4f) {  // opposite: any axis perpendicular to a
        axis = glm::cross(a, std::abs(a.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0));
    }
    axis = glm::normalize(axis);
    const float angle = std::acos(c) * t;
    // Rodrigues' rotation of a about the axis (a is perpendicular to it).
    return glm::normalize(a * std::cos(angle) + glm::cross(axis, a) * std::sin(angle));
}

TourCutPose interpolate_cut(const TourCutPose& a, const TourCutPose& b, float t, float radius) {
    t = std::clamp(t, 0.0f, 1.0f);
    if (t >= 1.0f) return b;
    if (!a.on && !b.on) return b;
    TourCutPose out;
    out.on = true;
    if (a.on && b.on) {
        out.normal = turn_normal(a.normal, b.normal, t);
        out.offset = a.offset + (b.offset - a.offset) * t;
        out.axis = t < 0.5f ? a.axis : b.axis;
    } else if (b.on) {  // sliding in from outside
        out.normal = b.normal;
        out.offset = radius + (b.offset - radius) * t;
        out.axis = b.axis;
    } else {  // sliding out
        out.normal = a.normal;
        out.offset = a.offset + (radius - a.offset) * t;
        out.axis = a.axis;
    }
    return out;
}

}  // namespace body::kiosk
