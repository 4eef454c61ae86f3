// Input-type dispatch for bodygen contours / bodygen build.
#include "builder/import/import.h"

#include <cctype>
#include <fstream>

#include "shared/input_file.h"

namespace body {

std::string structure_id_from_name(const std::string& name) {
    std::string id;
    for (char c : name) {
        const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
        id += keep ? c : '_';
    }
    return id;
}

SourceKind detect_source_kind(const std::string& path) {
    auto ends = [&](const char* suffix) {
        std::string lower;
        for (char c : path) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        return lower.ends_with(suffix);
    };
    if (ends(".json")) return SourceKind::ContourStack;
    if (ends(".nii") || ends(".nii.gz") || ends(".hdr") || ends(".img") || ends(".hdr.gz") || ends(".img.gz")) {
        return SourceKind::Nifti;
    }
    if (ends(".dcm")) return SourceKind::RtStruct;
    if (!check_regular_file(path)) return SourceKind::Unknown;
    std::ifstream in(path, std::ios::binary);
    char head[132] = {};
    if (in.read(head, sizeof head) && std::string(head + 128, 4) == "DICM") return SourceKind::RtStruct;
    return SourceKind::Unknown;
}

namespace {
Result<ContourStack> in_range(Result<ContourStack> stack, const std::string& path) {
    if (stack) {
        if (auto range = check_coordinate_range(*stack, path); !range) return range.error();
    }
    return stack;
}
}  // namespace

Result<ContourStack> load_any_contour_source(const std::string& path, const ImportOptions& options) {
    if (auto regular = check_regular_file(path); !regular) return regular.error();
    switch (detect_source_kind(path)) {
        case SourceKind::ContourStack: return read_contour_stack(path);
        case SourceKind::Nifti: return in_range(import_nifti_labels(path, options), path);
        case SourceKind::RtStruct: return in_range(import_rtstruct(path, options), path);
        case SourceKind::Unknown: break;
    }
    return input_error(path +
                       ": unknown input type (expected .contours.json, a NIfTI label volume .nii/.nii.gz, or a DICOM "
                       "RT-STRUCT .dcm)");
}

}  // namespace body
