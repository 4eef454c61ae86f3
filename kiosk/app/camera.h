#pragma once
// Orbit camera for the kiosk: a target point, azimuth around +Y, polar angle from
// +Y (clamped away from the poles so the view never flips) and a distance
// (clamped to the scene's scale). Pan moves the target in the view plane; focus
// moves target and distance to a model with an eased transition.
//
// Angles are radians, lengths scene units (mm), screen deltas pixels.
#include <glm/glm.hpp>

#include "kiosk/render/view.h"
#include "shared/geometry.h"

namespace body::kiosk {

struct CameraPose {
    glm::vec3 target{0.0f};
    float azimuth = 0.0f;
    float polar = 1.5707964f;
    float distance = 1.0f;
};

class OrbitCamera {
public:
    static constexpr float kMinPolar = 0.1745f;  // 10 degrees from the poles
    static constexpr float kMaxPolar = 2.9671f;  // 170 degrees
    static constexpr float kRadiansPerPixel = 0.01f;
    static constexpr double kFocusSeconds = 0.6;

    OrbitCamera() = default;
    // `scene_radius` sets the zoom limits: [0.05, 8] x scene radius.
    void configure(float fov_deg, float scene_radius);
    void set_viewport(int width, int height);
    void set_pose(const CameraPose& pose);  // clamps; cancels a transition

    // Gestures. `orbit` turns by pixels dragged; `zoom` divides the distance by
    // `factor` (>1 closer); `pan` moves the target so the scene follows the finger.
    void orbit(float dx_px, float dy_px);
    void rotate(float d_azimuth, float d_polar);
    void zoom(float factor);
    void pan(float dx_px, float dy_px);
    // Starts an eased transition to look at a sphere, filling ~60% of the view.
    void focus(const glm::vec3& center, float radius, double now);
    // Starts an eased transition to `pose` (used by the home button).
    void fly_to(const CameraPose& pose, double now);
    void update(double now);  // advances a transition
    bool transitioning() const { return transition_; }

    const CameraPose& pose() const { return pose_; }
    float min_distance() const { return min_distance_; }
    float max_distance() const { return max_distance_; }
    float fov_y() const { return fov_y_; }
    int width() const { return width_; }
    int height() const { return height_; }
    glm::vec3 eye() const;
    glm::mat4 view() const;
    // What the renderer draws from: this camera with its target and eye moved
    // by `shift_px` screen pixels (right, up; the kiosk's anti burn-in drift),
    // near and far hugging the sphere (center, radius) of what is drawn.
    render::View render_view(const glm::vec2& shift_px, const glm::vec3& scene_center, float scene_radius) const;
    glm::mat4 projection() const;
    // The ray through pixel (x, y) (origin top-left).
    Ray ray(float x, float y) const;
    // Projected radius in pixels of a sphere (for LOD weighting); 0 when behind the eye.
    float screen_radius(const glm::vec3& center, float radius) const;
    // Distance that fits a sphere of `radius` into the view.
    float fit_distance(float radius) const;

private:
    void clamp();

    CameraPose pose_;
    float fov_y_ = 0.698f;
    float min_distance_ = 0.01f, max_distance_ = 1e6f;
    int width_ = 1280, height_ = 800;
    bool transition_ = false;
    double transition_start_ = 0.0;
    CameraPose from_, to_;
};

}  // namespace body::kiosk
