// The source image on the kiosk's cut plane (contract in slices_volume.h).
#include "builder/exhibit/slices_volume.h"

#include <algorithm>
#include <cmath>

#include "builder/exhibit/orientation.h"

namespace body::exhibit {
namespace {

constexpr size_t kMaxTextureDim = 256;

// The 0.5th and 99.5th percentiles of the finite values; false when none.
bool robust_range(std::span<const float> values, float& lo, float& hi) {
    std::vector<float> v;
    v.reserve(values.size());
    for (float x : values)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty()) return false;
    const size_t a = v.size() / 200, b = v.size() - 1 - v.size() / 200;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(a), v.end());
    lo = v[a];
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(b), v.end());
    hi = v[b];
    return true;
}

// kiosk = M * scanner for the exhibit's models (orientation.h; exhibit.cpp's build_one).
glm::dmat3 scanner_to_kiosk(const std::array<Vec3, 3>& ras_axes) {
    glm::dmat3 e(1.0);  // rows: the data axes (column-major storage: e[col][row])
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) e[c][r] = ras_axes[size_t(r)][c];
    glm::dmat3 mir(1.0);
    std::array<Vec3, 3> proper = ras_axes;
    if (const int k = mirror_axis(ras_axes); k >= 0) {
        mir[k][k] = -1.0;
        proper[size_t(k)] = -proper[size_t(k)];
    }
    const auto rot = kiosk_rotation(proper);
    glm::dmat3 rm(1.0);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) rm[c][r] = rot[size_t(r)][size_t(c)];
    return rm * mir * e;
}

}  // namespace

Result<SliceVolume> slices_volume(const std::array<size_t, 3>& dim, std::span<const float> values,
                                  const double (&affine)[3][4], const std::array<Vec3, 3>& ras_axes,
                                  const std::string& source) {
    if (dim[0] * dim[1] * dim[2] == 0 || values.size() != dim[0] * dim[1] * dim[2])
        return input_error(source + ": empty grey-level volume");
    float lo = 0.0f, hi = 0.0f;
    if (!robust_range(values, lo, hi)) return input_error(source + ": no finite voxel in the grey-level volume");
    if (!(hi > lo))
        return input_error(source + ": the grey-level volume is flat (one level, " + std::to_string(lo) + ")");
    SliceVolume out;
    std::array<size_t, 3> step{};
    for (size_t a = 0; a < 3; ++a) {
        step[a] = (dim[a] + kMaxTextureDim - 1) / kMaxTextureDim;
        out.dims[a] = static_cast<uint32_t>((dim[a] + step[a] - 1) / step[a]);
    }
    out.voxels.resize(size_t(out.dims[0]) * out.dims[1] * out.dims[2]);
    const float scale = 255.0f / (hi - lo);
    size_t o = 0;
    for (size_t k = 0; k < out.dims[2]; ++k)
        for (size_t j = 0; j < out.dims[1]; ++j)
            for (size_t i = 0; i < out.dims[0]; ++i) {
                const float v = values[(k * step[2] * dim[1] + j * step[1]) * dim[0] + i * step[0]];
                const float g = std::isfinite(v) ? std::clamp((v - lo) * scale, 0.0f, 255.0f) : 0.0f;
                out.voxels[o++] = static_cast<uint8_t>(std::lround(g));
            }
    const glm::dmat3 m = scanner_to_kiosk(ras_axes);
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) {
            double x = 0.0;
            for (int q = 0; q < 3; ++q) x += m[q][r] * affine[q][c];
            if (c < 3) x *= static_cast<double>(step[size_t(c)]);
            out.affine[size_t(r * 4 + c)] = static_cast<float>(x + 0.0);
        }
    }
    return out;
}

std::array<Vec3, 3> volume_axes(const std::vector<Part>& parts, const std::vector<BuiltPart>& built,
                                const std::array<Vec3, 3>& fallback) {
    for (int pass = 0; pass < 2; ++pass)
        for (size_t i = 0; i < parts.size() && i < built.size(); ++i)
            if (!built[i].bpm.empty() && (pass == 1 || parts[i].contours)) return parts[i].ras_axes;
    return fallback;
}

}  // namespace body::exhibit
