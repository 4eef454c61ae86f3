#pragma once
// The manipulation sphere's rotate, scale and snap (the authoring window; the
// move is the kiosk app's Shift+drag). Plain functions over glm values, no GL.
//
// Rotate is an arcball: the sphere's disc on screen is the front half of a
// ball; the press and the pointer are points on it, and the model turns by the
// rotation taking one to the other, about the sphere's centre. Scale is the
// ratio of the pointer's distance from the sphere's centre to the press's,
// about the same centre. Snap rounds a transform to a grid step (translate),
// 15° (each Euler angle) and 0.1 (scale).
#include <glm/glm.hpp>

#include "shared/scene/scene.h"

namespace body::kiosk::author {

inline constexpr float kSnapDegrees = 15.0f;
inline constexpr float kSnapScale = 0.1f;

// A pixel as a unit vector on the ball whose screen disc is (centre,
// radius_px): view space, x right, y up, z towards the viewer. Outside the
// disc: on its rim (z = 0). Pixels have y down.
glm::vec3 arcball_point(const glm::vec2& pixel, const glm::vec2& centre, float radius_px);

// The rotation taking unit vector `from` to `to` (identity when they agree).
glm::mat3 rotation_between(const glm::vec3& from, const glm::vec3& to);

// `start` turned by the world rotation `rotation` about the world point
// `centre` (the model's placed centre stays put), then snapped when `snap`.
scene::Transform rotated(const scene::Transform& start, const glm::mat3& rotation, const glm::vec3& centre, bool snap);

// `start` scaled by `factor` about `centre`; with `snap` the resulting scale
// is a multiple of kSnapScale (at least one step).
scene::Transform scaled(const scene::Transform& start, float factor, const glm::vec3& centre, bool snap);

// The Euler angles (degrees; X then Y then Z, as SCENE.md's rotate) of a rotation.
glm::vec3 euler_degrees(const glm::mat3& rotation);
// A transform's rotation part (the Euler angles as a matrix).
glm::mat3 rotation_of(const scene::Transform& transform);

// The translate grid for a model of this bounding radius: the power of ten
// nearest below half the radius (1 mm for a 4 mm nerve, 10 mm for a brain).
float grid_step(float radius);
// Each translate component rounded to `grid`.
std::array<float, 3> snap_translate(const std::array<float, 3>& translate, float grid);

}  // namespace body::kiosk::author
