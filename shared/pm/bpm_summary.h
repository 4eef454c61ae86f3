#pragma once
// A .bpm file's structures as its INFO sections declare them, read without
// decoding anything: the file header, then section headers only, skipping
// (seeking past) every BASE and SPLT payload until each structure's INFO is in.
// The kiosk frames its camera and orders the decoding of thousands of files
// from these before any base mesh is decoded. Each INFO is checked as the
// full reader checks it (CRC, then read_info in bpm_container.h); a later section
// may still be corrupt, which the decoder reports.
#include <cstddef>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body::pm {

struct StructureSummary {
    Vec3f box_min{0.0f}, box_max{0.0f};  // quantization box (holds every vertex of every level)
    size_t base_triangles = 0;           // F0
    size_t full_triangles = 0;           // F
};

// Errors name the path, the section and the byte offset, as read_bpm does.
Result<std::vector<StructureSummary>> read_bpm_summary(const std::string& path);

}  // namespace body::pm
