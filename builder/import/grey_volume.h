#pragma once
// A NIfTI grey-level image (an anatomical template, a scan) read whole, for the
// cut plane's caps (`bodygen exhibit --slices-volume`, builder/exhibit/
// slices_volume.h). The header is checked as the label import checks it
// (nifti_header.h); the image must be 3-D with a numeric, non-complex type.
#include <array>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body {

struct GreyImage {
    std::array<size_t, 3> dim{1, 1, 1};
    double affine[3][4] = {};   // voxel index (i, j, k, 1) -> scanner mm (RAS+): sform, qform or pixdim
    std::vector<float> values;  // scaled by scl_slope/scl_inter, i fastest
};

// Errors: one line "PATH: reason" (bad header, 4-D data, unsupported type,
// truncated data, more voxels than the memory budget allows).
Result<GreyImage> read_grey_image(const std::string& path);

}  // namespace body
