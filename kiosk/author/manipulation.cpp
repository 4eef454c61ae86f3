// The manipulation sphere's rotate, scale and snap (contract in manipulation.h).
#include "kiosk/author/manipulation.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace body::kiosk::author {

glm::vec3 arcball_point(const glm::vec2& pixel, const glm::vec2& centre, float radius_px) {
    const float r = std::max(radius_px, 1.0f);
    glm::vec3 p((pixel.x - centre.x) / r, (centre.y - pixel.y) / r, 0.0f);
    const float d2 = p.x * p.x + p.y * p.y;
    if (d2 >= 1.0f) return glm::normalize(p);
    p.z = std::sqrt(1.0f - d2);
    return p;
}

glm::mat3 rotation_between(const glm::vec3& from, const glm::vec3& to) {
    const glm::vec3 axis = glm::cross(from, to);
    const float s = glm::length(axis), c = std::clamp(glm::dot(from, to), -1.0f, 1.0f);
    if (s < 1e-7f) return glm::mat3(1.0f);  // the same point (opposite points never come from one half ball)
    return glm::mat3(glm::rotate(glm::mat4(1.0f), std::atan2(s, c), axis / s));
}

glm::mat3 rotation_of(const scene::Transform& t) {
    glm::mat4 m(1.0f);
    m = glm::rotate(m, glm::radians(t.rotate_deg[2]), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(t.rotate_deg[1]), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(t.rotate_deg[0]), glm::vec3(1, 0, 0));
    return glm::mat3(m);
}

// R = Rz(c) Ry(b) Rx(a): row 2 is (-sin b, cos b sin a, cos b cos a); glm indexes [column][row].
glm::vec3 euler_degrees(const glm::mat3& r) {
    const float sb = std::clamp(-r[0][2], -1.0f, 1.0f);
    const float b = std::asin(sb);
    float a, c;
    if (std::abs(sb) < 0.99999f) {
        a = std::atan2(r[1][2], r[2][2]);
        c = std::atan2(r[0][1], r[0][0]);
    } else {  // gimbal lock: only a - c (or a + c) is defined; put it all in c
        a = 0.0f;
        c = std::atan2(-r[1][0], r[1][1]);
    }
    return glm::degrees(glm::vec3(a, b, c));
}

namespace {
float round_to(float v, float step) { return std::round(v / step) * step; }

// `start` with rotation `r` and scale `s`, moved so that `centre` stays where `start` put it.
scene::Transform about_centre(const scene::Transform& start, const glm::mat3& turn, float factor,
                              const glm::vec3& centre, const glm::mat3& r, float s) {
    scene::Transform t = start;
    const glm::vec3 old_t(start.translate[0], start.translate[1], start.translate[2]);
    const glm::vec3 new_t = centre + factor * (turn * (old_t - centre));
    t.translate = {new_t.x, new_t.y, new_t.z};
    const glm::vec3 e = euler_degrees(r);
    t.rotate_deg = {e.x, e.y, e.z};
    t.scale = s;
    return t;
}
}  // namespace

scene::Transform rotated(const scene::Transform& start, const glm::mat3& rotation, const glm::vec3& centre, bool snap) {
    const glm::mat3 before = rotation_of(start);
    glm::mat3 after = rotation * before;
    if (snap) {
        const glm::vec3 e = euler_degrees(after);
        scene::Transform t;
        t.rotate_deg = {round_to(e.x, kSnapDegrees), round_to(e.y, kSnapDegrees), round_to(e.z, kSnapDegrees)};
        after = rotation_of(t);
    }
    const glm::mat3 turn = after * glm::transpose(before);  // the turn actually applied
    return about_centre(start, turn, 1.0f, centre, after, start.scale);
}

scene::Transform scaled(const scene::Transform& start, float factor, const glm::vec3& centre, bool snap) {
    float s = start.scale * std::max(factor, 1e-3f);
    if (snap) s = std::max(kSnapScale, round_to(s, kSnapScale));
    return about_centre(start, glm::mat3(1.0f), s / start.scale, centre, rotation_of(start), s);
}

float grid_step(float radius) { return std::pow(10.0f, std::floor(std::log10(std::max(radius * 0.5f, 1e-6f)))); }

std::array<float, 3> snap_translate(const std::array<float, 3>& t, float grid) {
    return {round_to(t[0], grid), round_to(t[1], grid), round_to(t[2], grid)};
}

}  // namespace body::kiosk::author
