// The grey-level volume file of a bundle (contract in slice_volume.h).
#include "shared/scene/slice_volume.h"

#include <cmath>
#include <cstring>

namespace body {
namespace {

constexpr char kMagic[8] = {'B', 'O', 'D', 'Y', 'V', 'O', 'L', '1'};
constexpr size_t kHeader = 8 + 3 * 4 + 12 * 4;

uint32_t get_u32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int b = 0; b < 4; ++b) out.push_back(static_cast<uint8_t>(v >> (8 * b)));
}

}  // namespace

Result<SliceVolume> parse_slice_volume(std::span<const uint8_t> bytes, const std::string& path) {
    auto fail = [&](size_t at, const std::string& why) {
        return input_error(path + ": byte " + std::to_string(at) + ": " + why);
    };
    if (bytes.size() < kHeader) return fail(bytes.size(), "file ends inside the header");
    if (std::memcmp(bytes.data(), kMagic, 8) != 0) return fail(0, "not a grey-level volume (magic BODYVOL1)");
    SliceVolume v;
    uint64_t count = 1;
    for (size_t a = 0; a < 3; ++a) {
        v.dims[a] = get_u32(bytes.data() + 8 + 4 * a);
        if (v.dims[a] < 1 || v.dims[a] > kSliceVolumeMaxDim)
            return fail(8 + 4 * a, "dimension " + std::to_string(v.dims[a]) + " is outside 1.." +
                                       std::to_string(kSliceVolumeMaxDim));
        count *= v.dims[a];
    }
    for (size_t c = 0; c < 12; ++c) {
        const uint32_t u = get_u32(bytes.data() + 20 + 4 * c);
        std::memcpy(&v.affine[c], &u, 4);
        if (!std::isfinite(v.affine[c])) return fail(20 + 4 * c, "non-finite voxel-to-scene affine");
    }
    const auto& m = v.affine;
    const double det = double(m[0]) * (double(m[5]) * m[10] - double(m[6]) * m[9]) -
                       double(m[1]) * (double(m[4]) * m[10] - double(m[6]) * m[8]) +
                       double(m[2]) * (double(m[4]) * m[9] - double(m[5]) * m[8]);
    if (!(std::fabs(det) > 1e-12)) return fail(20, "singular voxel-to-scene affine");
    if (bytes.size() - kHeader != count)
        return fail(kHeader, std::to_string(bytes.size() - kHeader) + " bytes of voxels, the dims need " +
                                 std::to_string(count));
    v.voxels.assign(bytes.begin() + kHeader, bytes.end());
    return v;
}

std::vector<uint8_t> slice_volume_bytes(const SliceVolume& volume) {
    std::vector<uint8_t> out(kMagic, kMagic + 8);
    out.reserve(kHeader + volume.voxels.size());
    for (uint32_t d : volume.dims) put_u32(out, d);
    for (float f : volume.affine) {
        uint32_t u = 0;
        std::memcpy(&u, &f, 4);
        put_u32(out, u);
    }
    out.insert(out.end(), volume.voxels.begin(), volume.voxels.end());
    return out;
}

}  // namespace body
