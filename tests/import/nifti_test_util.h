#pragma once
// Writes synthetic label volumes with niftilib for the import tests.
#include <gtest/gtest.h>
#include <nifti1_io.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace body::test {

struct VolumeSpec {
    int nx = 1, ny = 1, nz = 1;
    double spacing[3] = {1.0, 1.0, 1.0};
    double origin[3] = {0.0, 0.0, 0.0};
    int dim4 = 1;  // > 1 writes a 4-D volume
};

inline std::filesystem::path temp_dir() {
    return std::filesystem::temp_directory_path() / ("body_import_test_" + std::to_string(::getpid()));
}

inline std::string temp_path(const std::string& name) {
    std::filesystem::create_directories(temp_dir());
    return (temp_dir() / name).string();
}

// Removes the test's temporary files at the end of the run; register once per
// test binary with ::testing::AddGlobalTestEnvironment(new TempCleanup).
class TempCleanup : public ::testing::Environment {
public:
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove_all(temp_dir(), ec);
    }
};

// Writes `data` (nx * ny * nz values, x fastest) as a NIfTI-1 file with an
// sform of diagonal `spacing` and translation `origin`.
template <typename T>
inline void write_nifti(const std::string& path, const VolumeSpec& spec, const std::vector<T>& data, int datatype) {
    const int dims[8] = {spec.dim4 > 1 ? 4 : 3, spec.nx, spec.ny, spec.nz, spec.dim4, 1, 1, 1};
    nifti_image* nim = nifti_make_new_nim(dims, datatype, 1);
    const size_t n = static_cast<size_t>(spec.nx) * spec.ny * spec.nz;
    for (int r = 0; r < spec.dim4; ++r) {
        std::memcpy(static_cast<char*>(nim->data) + r * n * sizeof(T), data.data(), n * sizeof(T));
    }
    nim->dx = nim->pixdim[1] = static_cast<float>(spec.spacing[0]);
    nim->dy = nim->pixdim[2] = static_cast<float>(spec.spacing[1]);
    nim->dz = nim->pixdim[3] = static_cast<float>(spec.spacing[2]);
    nim->qform_code = 0;
    nim->sform_code = 1;
    std::memset(&nim->sto_xyz, 0, sizeof nim->sto_xyz);
    for (int i = 0; i < 3; ++i) {
        nim->sto_xyz.m[i][i] = static_cast<float>(spec.spacing[i]);
        nim->sto_xyz.m[i][3] = static_cast<float>(spec.origin[i]);
    }
    nim->sto_xyz.m[3][3] = 1.0f;
    nifti_set_filenames(nim, path.c_str(), 0, 1);
    nifti_image_write(nim);
    nifti_image_free(nim);
}

}  // namespace body::test
