#pragma once
// A bundle's grey-level volume (scene.json cut_plane.volume): the source
// image that the kiosk shows on the cut plane's caps. Written by `bodygen
// exhibit --slices-volume` from a NIfTI volume, read by the kiosk, which has
// no NIfTI reader (it is cross-built without niftilib).
//
// File layout, little-endian:
//   8 bytes  magic "BODYVOL1"
//   3 uint32 dims nx, ny, nz (each 1..1024)
//   12 float32 voxel-to-scene affine, row-major 3x4: the scene (kiosk world,
//            before any model transform of the scene) position of voxel index
//            (i, j, k), i.e. of the voxel's centre
//   nx*ny*nz uint8 grey levels, i fastest, then j, then k
// Nothing may follow the voxels.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body {

struct SliceVolume {
    std::array<uint32_t, 3> dims{0, 0, 0};
    std::array<float, 12> affine{};  // row-major 3x4: voxel index -> scene
    std::vector<uint8_t> voxels;     // dims product, i fastest
};

inline constexpr uint32_t kSliceVolumeMaxDim = 1024;

// Parses the file's bytes; errors read "PATH: byte B: reason" (bad magic,
// dims out of range, a non-finite or singular affine, a size that does not
// match the dims).
Result<SliceVolume> parse_slice_volume(std::span<const uint8_t> bytes, const std::string& path);
// The file's bytes (the volume must be well formed: dims in range, voxels sized).
std::vector<uint8_t> slice_volume_bytes(const SliceVolume& volume);

}  // namespace body
