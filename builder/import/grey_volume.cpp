// A NIfTI grey-level image read whole (contract in grey_volume.h).
#include "builder/import/grey_volume.h"

#include <nifti1_io.h>

#include <cmath>
#include <memory>

#include "builder/import/nifti_header.h"

namespace body {

std::string check_data_length(const nifti_image& nim);  // nifti_import.cpp

namespace {

struct NiftiFree {
    void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};

template <typename T>
void convert(const void* data, size_t count, double slope, double inter, std::vector<float>& out) {
    const T* p = static_cast<const T*>(data);
    for (size_t i = 0; i < count; ++i) out[i] = static_cast<float>(static_cast<double>(p[i]) * slope + inter);
}

}  // namespace

Result<GreyImage> read_grey_image(const std::string& path) {
    const std::string where = path + ": ";
    auto header = read_nifti_header(path);
    if (!header) return header.error();
    const uint64_t voxels = header->data_bytes / uint64_t(header->bytes_per_voxel);
    if (header->data_bytes + 4 * voxels > label_volume_memory_budget())
        return runtime_error(where + "the image needs more memory than the budget allows");
    nifti_set_debug_level(0);
    std::unique_ptr<nifti_image, NiftiFree> nim(nifti_image_read(path.c_str(), 0));
    if (!nim) return input_error(where + "not a readable NIfTI-1/ANALYZE header");
    for (int d = 4; d <= nim->dim[0] && d <= 7; ++d)
        if (nim->dim[d] > 1)
            return input_error(where + "a grey-level volume is 3-D, but dim[" + std::to_string(d) +
                               "] = " + std::to_string(nim->dim[d]));
    if (const std::string reason = check_data_length(*nim); !reason.empty()) return input_error(where + reason);
    if (nifti_image_load(nim.get()) != 0 || !nim->data) return input_error(where + "image data unreadable");
    GreyImage g;
    for (size_t d = 0; d < 3; ++d) g.dim[d] = static_cast<size_t>(nim->dim[d + 1]);
    const size_t count = g.dim[0] * g.dim[1] * g.dim[2];
    double slope = nim->scl_slope, inter = nim->scl_inter;
    if (slope == 0.0 || !std::isfinite(slope) || !std::isfinite(inter)) slope = 1.0, inter = 0.0;
    g.values.resize(count);
    switch (nim->datatype) {
        case DT_UINT8: convert<uint8_t>(nim->data, count, slope, inter, g.values); break;
        case DT_INT8: convert<int8_t>(nim->data, count, slope, inter, g.values); break;
        case DT_INT16: convert<int16_t>(nim->data, count, slope, inter, g.values); break;
        case DT_UINT16: convert<uint16_t>(nim->data, count, slope, inter, g.values); break;
        case DT_INT32: convert<int32_t>(nim->data, count, slope, inter, g.values); break;
        case DT_UINT32: convert<uint32_t>(nim->data, count, slope, inter, g.values); break;
        case DT_INT64: convert<int64_t>(nim->data, count, slope, inter, g.values); break;
        case DT_UINT64: convert<uint64_t>(nim->data, count, slope, inter, g.values); break;
        case DT_FLOAT32: convert<float>(nim->data, count, slope, inter, g.values); break;
        case DT_FLOAT64: convert<double>(nim->data, count, slope, inter, g.values); break;
        default:
            return input_error(where + "unsupported data type " + nifti_datatype_string(nim->datatype) +
                               " for a grey-level volume");
    }
    const mat44* m = nim->sform_code > 0 ? &nim->sto_xyz : nim->qform_code > 0 ? &nim->qto_xyz : nullptr;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) {
            const float pix = nim->pixdim[r + 1] > 0 ? nim->pixdim[r + 1] : 1.0f;
            g.affine[r][c] = m ? m->m[r][c] : (r == c ? pix : 0.0);
            if (!std::isfinite(g.affine[r][c])) return input_error(where + "non-finite voxel-to-scanner transform");
        }
    return g;
}

}  // namespace body
