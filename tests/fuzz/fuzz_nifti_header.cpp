// libFuzzer target for the NIfTI-1 header check: facts or one error line
// naming the file and a header byte, never a crash; accepted dims positive.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "builder/import/nifti_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    auto facts = body::check_nifti_header({data, size}, "fuzz.nii");
    if (!facts.ok()) {
        const std::string& m = facts.error().message;
        if (m.rfind("fuzz.nii: header byte ", 0) != 0 || m.find('\n') != std::string::npos) std::abort();
        return 0;
    }
    for (int64_t d : facts->dim)
        if (d < 1) std::abort();
    if (facts->bytes_per_voxel < 1) std::abort();
    return 0;
}
