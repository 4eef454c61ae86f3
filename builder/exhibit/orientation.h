#pragma once
// Where an exhibit's camera starts: anatomical views from the source's patient
// orientation, not from its array axes.
//
// The kiosk's world has +Y up and its orbit camera looks down -Z at azimuth 0
// (kiosk/app/camera.cpp). An exhibit turns the models so that the patient's
// superior is +Y, anterior +Z and left +X (a proper rotation, so meshes keep
// their handedness); the views are then fixed azimuths: anterior 0, left
// lateral 90, posterior 180, right lateral -90, all head up.
#include <array>
#include <optional>
#include <string>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body::exhibit {

enum class View { Anterior, Left, Posterior, Right };

Result<View> parse_view(const std::string& name);  // "anterior", "left", "posterior", "right"
float view_azimuth_deg(View view);

// Three letters naming the patient direction of the data's +x, +y, +z, e.g.
// "RAS" (NIfTI scanner space) or "LPS" (DICOM patient space): R/L, A/P, S/I, each
// axis once. Returns the unit directions in RAS+.
Result<std::array<Vec3, 3>> parse_orientation(const std::string& letters);

// A left-handed (mirrored) frame cannot be turned into the kiosk's by a
// rotation: the data must be mirrored first. Returns the data axis to negate
// (the one running closest to left-right), or -1 for a proper frame.
int mirror_axis(const std::array<Vec3, 3>& ras_axes);

// The rotation taking data coordinates (axes given in RAS+, a proper frame:
// mirror first, see mirror_axis) to kiosk coordinates, as the scene manifest's
// Euler angles (applied X, then Y, then Z; degrees).
std::array<float, 3> kiosk_rotation_deg(const std::array<Vec3, 3>& ras_axes);

// The same rotation as a row-major 3x3 matrix (kiosk = M * data), for tests and exporters.
std::array<std::array<double, 3>, 3> kiosk_rotation(const std::array<Vec3, 3>& ras_axes);

}  // namespace body::exhibit
