#pragma once
// The visitor's cut plane, without GL: whether it is on, whether gestures move
// it or the camera, its axis preset and where it lies. The renderer takes it
// as render::CutPlane (plane()) and removes the half its normal points into.
//
// Behaviour (KioskApp routes the gestures here while editing() is true):
//   - the Cut button cycles off -> on, gestures move the plane -> on, gestures
//     move the camera -> off; turning it on with a model of a group selected
//     cuts that group alone (group()), otherwise every model;
//   - the Axis button cycles the presets axial -> coronal -> sagittal; a preset
//     puts the plane through the scene's centre, its normal (the removed side)
//     turned toward the eye;
//   - a one-finger drag (Orbit gesture; mouse: left drag) moves the plane along
//     its normal by the drag's component along the normal's image on screen
//     (straight up the screen when the normal faces the eye), one pixel = one
//     pixel's worth of scene at the camera's target; the plane stays within
//     the scene's bounding sphere;
//   - two fingers (Pan gesture; mouse: middle drag) tilt it: horizontal motion
//     turns the normal about the camera's up axis, vertical motion about its
//     right axis, kTiltRadiansPerPixel, around the plane's point nearest the
//     scene's centre.
// Kiosk world: +Y superior, +Z anterior, +X the patient's left
// (builder/exhibit/orientation.h), so axial = Y, coronal = Z, sagittal = X
// unless the scene says otherwise (scene::CutPlaneSettings).
#include <array>
#include <glm/glm.hpp>
#include <string>

#include "kiosk/render/cut_plane.h"

namespace body::kiosk {

class OrbitCamera;

enum class CutAxis { Axial, Coronal, Sagittal };
const char* cut_axis_name(CutAxis axis);  // "axial", "coronal", "sagittal"

class CutPlane {
public:
    static constexpr float kTiltRadiansPerPixel = 0.005f;

    // The scene's bounding sphere and each preset's world normal (unit).
    void configure(glm::vec3 scene_center, float scene_radius, const std::array<glm::vec3, 3>& axes);
    // Off -> editing -> fixed -> off; `group` is the group a turned-on plane cuts (-1: all).
    void cycle(const OrbitCamera& camera, int group);
    void set_axis(CutAxis axis, const OrbitCamera& camera);
    void next_axis(const OrbitCamera& camera);
    void off();
    // One-finger drag of (dx, dy) pixels; two-finger tilt.
    void drag(float dx, float dy, const OrbitCamera& camera);
    void tilt(float dx, float dy, const OrbitCamera& camera);

    bool on() const { return on_; }
    bool editing() const { return on_ && editing_; }
    CutAxis axis() const { return axis_; }
    int group() const { return group_; }
    glm::vec3 normal() const { return normal_; }  // unit, into the removed half
    float offset() const { return offset_; }      // plane's signed distance from the scene centre along normal()
    glm::vec3 point() const { return center_ + normal_ * offset_; }
    render::CutPlane plane() const;  // enabled only while on()

private:
    void face_eye(const OrbitCamera& camera);

    glm::vec3 center_{0.0f};
    float radius_ = 1.0f;
    std::array<glm::vec3, 3> axes_{glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)};
    bool on_ = false, editing_ = false;
    CutAxis axis_ = CutAxis::Axial;
    int group_ = -1;
    glm::vec3 normal_{0.0f, 1.0f, 0.0f};
    float offset_ = 0.0f;
};

}  // namespace body::kiosk
