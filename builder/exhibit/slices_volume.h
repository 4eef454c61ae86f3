#pragma once
// The source image on the kiosk's cut plane (`bodygen exhibit --slices-volume`,
// scene.json cut_plane.volume): a grey-level image windowed to 8 bits and
// placed in the kiosk's world exactly as the exhibit places its models, so a
// cap on a slice shows the image that slice was traced on.
//
// Contract:
// - Window: the image's 0.5th and 99.5th percentiles (robust against a few hot
//   voxels) map to 0 and 255; non-finite voxels are 0.
// - Placement: the voxel-to-scanner `affine` (RAS+ mm), then the data frame of
//   `ras_axes` (dot with each axis, as the label import's contours are), the
//   exhibit's mirror and kiosk rotation (orientation.h). So the models and the
//   volume agree when `ras_axes` is the models' own.
// - Size: an axis over 256 voxels (the smallest GL_MAX_3D_TEXTURE_SIZE of
//   GLES 3.0) keeps every s-th voxel, s = ceil(n / 256).
#include <array>
#include <span>
#include <string>
#include <vector>

#include "builder/exhibit/exhibit.h"
#include "shared/error.h"
#include "shared/scene/slice_volume.h"

namespace body::exhibit {

// Errors name `source`: an empty image, no finite voxel, a flat image (one grey level).
Result<SliceVolume> slices_volume(const std::array<size_t, 3>& dim, std::span<const float> values,
                                  const double (&affine)[3][4], const std::array<Vec3, 3>& ras_axes,
                                  const std::string& source);

// The axes the volume is placed by: the first built contour part's, else the
// first built part's, else `fallback`.
std::array<Vec3, 3> volume_axes(const std::vector<Part>& parts, const std::vector<BuiltPart>& built,
                                const std::array<Vec3, 3>& fallback);

}  // namespace body::exhibit
