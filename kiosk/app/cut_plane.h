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
//     scene's centre;
//   - snapping: when the scene gives its input slices (set_slices(), scene.json
//     cut_plane.slice_normal / slice_at), a plane dragged or tilted to within
//     kSnapDegrees of the slices' normal and kSnapPixels (pixels' worth of
//     scene at the camera's target, as the drag) of a slice lies exactly on
//     it, normal and all, so the cap is that slice's traced contour; the
//     gesture goes on from where the visitor's fingers are, so dragging on
//     past the tolerance leaves the slice;
//   - a tour step may set the plane (set_fixed()): on, gestures move the
//     camera, every model cut.
// Kiosk world: +Y superior, +Z anterior, +X the patient's left
// (builder/exhibit/orientation.h), so axial = Y, coronal = Z, sagittal = X
// unless the scene says otherwise (scene::CutPlaneSettings).
#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kiosk/render/cut_plane.h"

namespace body::kiosk {

class OrbitCamera;

enum class CutAxis { Axial, Coronal, Sagittal };
const char* cut_axis_name(CutAxis axis);  // "axial", "coronal", "sagittal"

class CutPlane {
public:
    static constexpr float kTiltRadiansPerPixel = 0.005f;
    static constexpr float kSnapPixels = 12.0f, kSnapDegrees = 2.0f;

    // The scene's bounding sphere and each preset's world normal (unit).
    void configure(glm::vec3 scene_center, float scene_radius, const std::array<glm::vec3, 3>& axes);
    // Off -> editing -> fixed -> off; `group` is the group a turned-on plane cuts (-1: all).
    void cycle(const OrbitCamera& camera, int group);
    void set_axis(CutAxis axis, const OrbitCamera& camera);
    void next_axis(const OrbitCamera& camera);
    void off();
    // A fixed plane (a tour step's): `normal` (into the removed half; unit or
    // not, non-zero) at `offset` from the scene's centre, cutting every model;
    // `axis`: the preset it came from (the Axis button shows it), if any.
    void set_fixed(glm::vec3 normal, float offset, std::optional<CutAxis> axis = std::nullopt);
    glm::vec3 axis_normal(CutAxis axis) const { return axes_[static_cast<size_t>(axis)]; }
    // The input slices to snap to: world planes dot(normal, p) = at[i]
    // (normal unit or not; empty `at`: no snapping).
    void set_slices(glm::vec3 normal, std::vector<float> at);
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
    float radius() const { return radius_; }        // the scene's bounding sphere (offsets stay within it)
    render::CutPlane plane() const;                 // enabled only while on()
    int snapped_slice() const { return snapped_; }  // the index into set_slices()'s `at` the plane lies on; -1: none

private:
    void face_eye(const OrbitCamera& camera);
    // The gestures move raw_normal_/raw_offset_; the plane is them, snapped.
    void snap(const OrbitCamera& camera);
    void keep_raw() { raw_normal_ = normal_, raw_offset_ = offset_, snapped_ = -1; }

    glm::vec3 center_{0.0f};
    float radius_ = 1.0f;
    std::array<glm::vec3, 3> axes_{glm::vec3(0, 1, 0), glm::vec3(0, 0, 1), glm::vec3(1, 0, 0)};
    bool on_ = false, editing_ = false;
    CutAxis axis_ = CutAxis::Axial;
    int group_ = -1;
    glm::vec3 normal_{0.0f, 1.0f, 0.0f};
    float offset_ = 0.0f;
    glm::vec3 raw_normal_{0.0f, 1.0f, 0.0f};
    float raw_offset_ = 0.0f;
    glm::vec3 slice_normal_{0.0f, 1.0f, 0.0f};
    std::vector<float> slice_at_;
    int snapped_ = -1;
};

}  // namespace body::kiosk
