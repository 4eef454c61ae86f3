#pragma once
// A tour step's cut plane between two steps, as the camera moves (tour.h):
// the plane a step sets (steps[].cut) is reached over the step's `duration`
// with its easing, not set at once.
//   - on to on: the normal turns along the great circle between the two
//     normals, the offset (from the scene's centre along the normal) moves
//     linearly;
//   - off to on: the plane slides in along its normal from the edge of the
//     scene's bounding sphere (offset = radius: nothing removed yet);
//   - on to off: it slides out the same way and turns off at the end.
#include <glm/glm.hpp>
#include <optional>

#include "kiosk/app/cut_plane.h"

namespace body::kiosk {

struct TourCutPose {
    bool on = false;
    glm::vec3 normal{0.0f, 1.0f, 0.0f};  // unit, into the removed half
    float offset = 0.0f;
    std::optional<CutAxis> axis;  // the preset the plane came from, if any
};

// The plane a fraction `t` (already eased, clamped to [0, 1]) of the way from
// `a` to `b` in a scene of bounding radius `radius`; t = 0 gives `a`, t = 1 `b`.
TourCutPose interpolate_cut(const TourCutPose& a, const TourCutPose& b, float t, float radius);

// The normal `t` of the way from unit `a` to unit `b` along the great circle
// (opposite normals turn about a perpendicular axis); unit.
glm::vec3 turn_normal(glm::vec3 a, glm::vec3 b, float t);

}  // namespace body::kiosk
