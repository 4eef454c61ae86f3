// Orbit camera: spherical coordinates around a target, eased focus transitions.
#include "kiosk/app/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace body::kiosk {

namespace {

float ease(float t) { return t * t * (3.0f - 2.0f * t); }

// Shortest signed angle from a to b.
float angle_delta(float a, float b) {
    const float two_pi = 6.2831853f;
    float d = std::fmod(b - a, two_pi);
    if (d > 3.1415927f) d -= two_pi;
    if (d < -3.1415927f) d += two_pi;
    return d;
}

}  // namespace

void OrbitCamera::configure(float fov_deg, float scene_radius) {
    fov_y_ = glm::radians(fov_deg);
    const float r = std::max(scene_radius, 1e-3f);
    min_distance_ = 0.05f * r;
    max_distance_ = 8.0f * r;
    clamp();
}

void OrbitCamera::set_viewport(int width, int height) {
    width_ = std::max(width, 1);
    height_ = std::max(height, 1);
}

void OrbitCamera::set_pose(const CameraPose& pose) {
    pose_ = pose;
    transition_ = false;
    clamp();
}

void OrbitCamera::clamp() {
    pose_.polar = std::clamp(pose_.polar, kMinPolar, kMaxPolar);
    pose_.distance = std::clamp(pose_.distance, min_distance_, max_distance_);
    pose_.azimuth = std::remainder(pose_.azimuth, 6.2831853f);
}

void OrbitCamera::orbit(float dx_px, float dy_px) { rotate(-dx_px * kRadiansPerPixel, -dy_px * kRadiansPerPixel); }

void OrbitCamera::rotate(float d_azimuth, float d_polar) {
    transition_ = false;
    pose_.azimuth += d_azimuth;
    pose_.polar += d_polar;
    clamp();
}

void OrbitCamera::zoom(float factor) {
    if (!(factor > 0.0f) || !std::isfinite(factor)) return;
    transition_ = false;
    pose_.distance /= factor;
    clamp();
}

void OrbitCamera::pan(float dx_px, float dy_px) {
    transition_ = false;
    const float units_per_px = 2.0f * pose_.distance * std::tan(fov_y_ * 0.5f) / static_cast<float>(height_);
    const glm::mat4 v = view();
    const glm::vec3 right(v[0][0], v[1][0], v[2][0]);
    const glm::vec3 up(v[0][1], v[1][1], v[2][1]);
    pose_.target += (-dx_px * right + dy_px * up) * units_per_px;
}

float OrbitCamera::fit_distance(float radius) const {
    const float half = std::min(fov_y_, fov_y_ * static_cast<float>(width_) / static_cast<float>(height_)) * 0.5f;
    return radius / std::sin(half) / 0.6f;
}

void OrbitCamera::focus(const glm::vec3& center, float radius, double now) {
    from_ = pose_;
    to_ = pose_;
    to_.target = center;
    to_.distance = std::clamp(fit_distance(radius), min_distance_, max_distance_);
    transition_ = true;
    transition_start_ = now;
}

void OrbitCamera::fly_to(const CameraPose& pose, double now) {
    from_ = pose_;
    to_ = pose;
    to_.polar = std::clamp(to_.polar, kMinPolar, kMaxPolar);
    to_.distance = std::clamp(to_.distance, min_distance_, max_distance_);
    transition_ = true;
    transition_start_ = now;
}

void OrbitCamera::update(double now) {
    if (!transition_) return;
    const float t = static_cast<float>(std::clamp((now - transition_start_) / kFocusSeconds, 0.0, 1.0));
    const float e = ease(t);
    pose_.target = glm::mix(from_.target, to_.target, e);
    pose_.distance = from_.distance + (to_.distance - from_.distance) * e;
    pose_.azimuth = from_.azimuth + angle_delta(from_.azimuth, to_.azimuth) * e;
    pose_.polar = from_.polar + (to_.polar - from_.polar) * e;
    if (t >= 1.0f) transition_ = false;
    clamp();
}

glm::vec3 OrbitCamera::eye() const {
    const float s = std::sin(pose_.polar);
    const glm::vec3 dir(s * std::sin(pose_.azimuth), std::cos(pose_.polar), s * std::cos(pose_.azimuth));
    return pose_.target + dir * pose_.distance;
}

glm::mat4 OrbitCamera::view() const { return glm::lookAt(eye(), pose_.target, glm::vec3(0.0f, 1.0f, 0.0f)); }

render::View OrbitCamera::render_view(const glm::vec2& shift_px, const glm::vec3& scene_center,
                                      float scene_radius) const {
    const float units_per_px = 2.0f * pose_.distance * std::tan(fov_y_ * 0.5f) / static_cast<float>(height_);
    const glm::mat4 v = view();
    const glm::vec3 right(v[0][0], v[1][0], v[2][0]), up(v[0][1], v[1][1], v[2][1]);
    const glm::vec3 shift = (-shift_px.x * right + shift_px.y * up) * units_per_px;
    render::View rv;
    rv.eye = eye() + shift;
    rv.target = pose_.target + shift;
    rv.fov_y_deg = glm::degrees(fov_y_);
    const float dist = glm::length(rv.eye - scene_center);
    rv.near_plane = std::max(dist - scene_radius * 1.5f, pose_.distance * 0.01f);
    rv.far_plane = dist + scene_radius * 1.5f + pose_.distance;
    return rv;
}

glm::mat4 OrbitCamera::projection() const {
    const float aspect = static_cast<float>(width_) / static_cast<float>(height_);
    return glm::perspective(fov_y_, aspect, std::max(pose_.distance * 0.01f, 1e-4f), pose_.distance * 20.0f);
}

Ray OrbitCamera::ray(float x, float y) const {
    const float ndc_x = 2.0f * (x + 0.5f) / static_cast<float>(width_) - 1.0f;
    const float ndc_y = 1.0f - 2.0f * (y + 0.5f) / static_cast<float>(height_);
    const glm::mat4 inv = glm::inverse(projection() * view());
    glm::vec4 a = inv * glm::vec4(ndc_x, ndc_y, -1.0f, 1.0f);
    glm::vec4 b = inv * glm::vec4(ndc_x, ndc_y, 1.0f, 1.0f);
    const glm::vec3 pa = glm::vec3(a) / a.w, pb = glm::vec3(b) / b.w;
    return Ray{eye(), glm::normalize(pb - pa)};
}

float OrbitCamera::screen_radius(const glm::vec3& center, float radius) const {
    const glm::vec4 c = view() * glm::vec4(center, 1.0f);
    const float depth = -c.z;
    if (depth <= radius * 0.01f) return static_cast<float>(height_);  // the eye is inside or at it
    return radius / (depth * std::tan(fov_y_ * 0.5f)) * 0.5f * static_cast<float>(height_);
}

}  // namespace body::kiosk
