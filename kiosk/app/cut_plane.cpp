// The visitor's cut plane: presets, the drag along the normal and the tilt
// (contract in cut_plane.h).
#include "kiosk/app/cut_plane.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/app/camera.h"

namespace body::kiosk {

const char* cut_axis_name(CutAxis axis) {
    switch (axis) {
        case CutAxis::Coronal: return "coronal";
        case CutAxis::Sagittal: return "sagittal";
        case CutAxis::Axial: break;
    }
    return "axial";
}

void CutPlane::configure(glm::vec3 scene_center, float scene_radius, const std::array<glm::vec3, 3>& axes) {
    center_ = scene_center;
    radius_ = std::max(scene_radius, 1e-6f);
    for (size_t i = 0; i < axes.size(); ++i)
        axes_[i] = glm::length(axes[i]) > 0.0f ? glm::normalize(axes[i]) : glm::vec3(0.0f, 1.0f, 0.0f);
    normal_ = axes_[static_cast<size_t>(axis_)];
    keep_raw();
}

void CutPlane::face_eye(const OrbitCamera& camera) {
    // Clearly away from the eye: an eye level with the plane keeps the preset's direction.
    const glm::vec3 to_eye = camera.eye() - point();
    if (glm::dot(normal_, to_eye) < -1e-3f * glm::length(to_eye)) {
        normal_ = -normal_;
        offset_ = -offset_;
    }
    keep_raw();
}

void CutPlane::set_axis(CutAxis axis, const OrbitCamera& camera) {
    axis_ = axis;
    normal_ = axes_[static_cast<size_t>(axis)];
    offset_ = 0.0f;
    face_eye(camera);
    snap(camera);
}

void CutPlane::next_axis(const OrbitCamera& camera) {
    set_axis(static_cast<CutAxis>((static_cast<int>(axis_) + 1) % 3), camera);
}

void CutPlane::cycle(const OrbitCamera& camera, int group) {
    if (!on_) {
        on_ = editing_ = true;
        group_ = group;
        set_axis(axis_, camera);
    } else if (editing_) {
        editing_ = false;
    } else {
        off();
    }
}

void CutPlane::off() {
    on_ = editing_ = false;
    group_ = -1;
}

void CutPlane::set_fixed(glm::vec3 normal, float offset, std::optional<CutAxis> axis) {
    if (axis) axis_ = *axis;
    on_ = true;
    editing_ = false;
    group_ = -1;
    normal_ = glm::length(normal) > 0.0f ? glm::normalize(normal) : axes_[0];
    offset_ = std::clamp(offset, -radius_, radius_);
    keep_raw();
}

void CutPlane::set_slices(glm::vec3 normal, std::vector<float> at) {
    const float len = glm::length(normal);
    slice_at_.clear();
    if (len <= 0.0f) return;
    slice_normal_ = normal / len;
    for (float a : at) slice_at_.push_back(a / len);  // the same planes with a unit normal
}

namespace {

float world_per_pixel(const OrbitCamera& camera) {
    const float h = static_cast<float>(std::max(camera.height(), 1));
    return 2.0f * camera.pose().distance * std::tan(camera.fov_y() * 0.5f) / h;
}

}  // namespace

void CutPlane::snap(const OrbitCamera& camera) {
    normal_ = raw_normal_;
    offset_ = raw_offset_;
    snapped_ = -1;
    const float facing = glm::dot(raw_normal_, slice_normal_);
    if (slice_at_.empty() || std::abs(facing) < std::cos(glm::radians(kSnapDegrees))) return;
    const float sign = facing >= 0.0f ? 1.0f : -1.0f;
    // Where the plane's point nearest the centre lies along the slices' normal.
    const float base = glm::dot(slice_normal_, center_);
    const float at = glm::dot(slice_normal_, center_ + raw_normal_ * raw_offset_);
    const float tolerance = kSnapPixels * world_per_pixel(camera);
    float best = tolerance;
    for (size_t i = 0; i < slice_at_.size(); ++i) {
        const float off = sign * (slice_at_[i] - base);
        if (std::abs(slice_at_[i] - at) <= best && std::abs(off) <= radius_) {
            best = std::abs(slice_at_[i] - at);
            snapped_ = static_cast<int>(i);
        }
    }
    if (snapped_ < 0) return;
    normal_ = sign * slice_normal_;
    offset_ = sign * (slice_at_[static_cast<size_t>(snapped_)] - base);
}

void CutPlane::drag(float dx, float dy, const OrbitCamera& camera) {
    const float h = static_cast<float>(std::max(camera.height(), 1));
    const float world_per_px = world_per_pixel(camera);
    // The normal's image on screen, in pixels per world unit (y down, as the drag).
    const glm::mat4 pv = camera.projection() * camera.view();
    auto screen = [&](glm::vec3 p) {
        const glm::vec4 c = pv * glm::vec4(p, 1.0f);
        return glm::vec2(c.x / c.w * 0.5f * static_cast<float>(camera.width()), -c.y / c.w * 0.5f * h);
    };
    const glm::vec3 p = point();
    const float step = radius_ * 0.1f;
    const glm::vec2 along = (screen(p + normal_ * step) - screen(p)) / step;
    const float len = glm::length(along);
    float move = 0.0f;
    if (len * world_per_px > 0.2f)  // the normal shows on screen: follow it
        move = glm::dot(glm::vec2(dx, dy), along / len) * world_per_px;
    else  // it faces the eye: up the screen moves the plane toward the eye
        move = -dy * world_per_px * (glm::dot(normal_, camera.eye() - p) >= 0.0f ? 1.0f : -1.0f);
    raw_offset_ = std::clamp(raw_offset_ + move, -radius_, radius_);
    snap(camera);
}

void CutPlane::tilt(float dx, float dy, const OrbitCamera& camera) {
    const glm::mat4 view = camera.view();
    const glm::vec3 right(view[0][0], view[1][0], view[2][0]), up(view[0][1], view[1][1], view[2][1]);
    const glm::vec3 p = center_ + raw_normal_ * raw_offset_;
    glm::mat4 turn = glm::rotate(glm::mat4(1.0f), dx * kTiltRadiansPerPixel, up);
    turn = glm::rotate(turn, dy * kTiltRadiansPerPixel, right);
    raw_normal_ = glm::normalize(glm::vec3(turn * glm::vec4(raw_normal_, 0.0f)));
    // The plane keeps the point it turned around.
    raw_offset_ = std::clamp(glm::dot(p - center_, raw_normal_), -radius_, radius_);
    snap(camera);
}

render::CutPlane CutPlane::plane() const {
    render::CutPlane c;
    c.enabled = on_;
    c.plane = glm::vec4(normal_, -glm::dot(normal_, point()));
    return c;
}

}  // namespace body::kiosk
