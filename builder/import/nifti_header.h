#pragma once
// The NIfTI-1 / ANALYZE 7.5 header checked before niftilib sees it: niftilib
// "repairs" zero or negative dims, ignores a wrong magic and sizeof_hdr, and
// prints its own messages; we refuse those headers with one located line, and
// bound what the volume may cost in memory before any voxel is read.
#include <cstdint>
#include <span>
#include <string>

#include "shared/error.h"

namespace body {

inline constexpr size_t kNiftiHeaderSize = 348;

struct NiftiHeaderFacts {
    int64_t dim[3] = {1, 1, 1};
    int bytes_per_voxel = 0;   // from bitpix
    uint64_t data_bytes = 0;   // dim product times bytes per voxel
    uint64_t data_offset = 0;  // vox_offset (single-file .nii), 0 for a .hdr/.img pair
    bool single_file = true;   // magic "n+1"
};

// Checks the first 348 bytes of a header (either byte order): sizeof_hdr =
// 348, magic "n+1\0" (.nii) or "ni1\0" (.hdr; four zero bytes for ANALYZE
// 7.5), 1 <= dim[0] <= 7, dim[1..3] >= 1, dim[4..dim[0]] <= 1 and bitpix a
// positive multiple of 8. Errors: "PATH: header byte B: reason".
Result<NiftiHeaderFacts> check_nifti_header(std::span<const uint8_t> header, const std::string& path);

// Reads the header of `path` (plain or gzip) and checks it as above.
Result<NiftiHeaderFacts> read_nifti_header(const std::string& path);

// Bytes a label import may hold at once (the raw data plus one int32 per
// voxel): half the physical memory, lowered to 3/4 of RLIMIT_AS when set.
uint64_t label_volume_memory_budget();

}  // namespace body
