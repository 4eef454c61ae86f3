#pragma once
// Separable Gaussian blur of a 3-D float volume, in place.
//
// Contract:
// - `field` holds size[0] * size[1] * size[2] values, x fastest.
// - Axis d is convolved with a Gaussian of standard deviation `sigma[d]`
//   (in voxels of that axis: a blur isotropic in millimetres on anisotropic
//   voxels has a smaller sigma on the longer axes) truncated at radius
//   ceil(3 sigma[d]) and
//   normalised to sum 1, so a constant region away from the edges stays
//   constant and the sum of the blurred fields of disjoint indicators stays
//   at most 1 everywhere. Values beyond the volume count as 0: pad the volume
//   by the radius to blur without losing mass at its edges.
// - An axis with sigma <= 0 is left as it is. Scratch: a line along x and
//   up to 4096 values of each line along y or z (not a copy of the field).
//   Sums are in float (rounding ~1e-7 of the values).
#include <cstddef>
#include <span>

namespace body {

// The truncation radius in voxels for `sigma` (0 for sigma <= 0).
size_t gaussian_radius(double sigma);

void gaussian_blur_3d(std::span<float> field, const size_t size[3], const double sigma[3]);

}  // namespace body
