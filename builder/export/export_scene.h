#pragma once
// What `bodygen export` writes, whatever it reads: named, coloured meshes with
// their group and the scene's placement.
//
// Sources: a kiosk bundle (BUNDLE/ or its scene.json: models, groups, colours,
// transforms), a .bpm file (one model per structure) or an OBJ file (one model
// per object). Progressive meshes are taken at `lod` (a ratio of the full
// triangle count in (0, 1], as `bodygen extract --ratio`), positions as the
// kiosk decodes them (within ProgressiveMesh::quantization_bound() of the
// builder's) and the file's unit normals.
#include <array>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"
#include "shared/mesh.h"

namespace body::exporter {

struct ExportModel {
    std::string name;   // unique in the scene
    std::string group;  // empty: none
    Mesh mesh;          // mesh.color is the model's colour (linear RGB in [0, 1])
    // Placement: translate * Rz * Ry * Rx * scale, as the kiosk applies it (row-major 4x4).
    std::array<std::array<double, 4>, 4> matrix{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    float quantization_bound = 0.0f;  // how far positions may be from the builder's (0: exact)
};

struct ExportScene {
    std::vector<ExportModel> models;
    std::vector<std::string> groups;  // in manifest order
};

Result<ExportScene> load_export_scene(const std::string& path, double lod);

// The placement applied to one point / direction (for formats without a scene graph).
Vec3 place_point(const ExportModel& m, const Vec3& p);
Vec3 place_normal(const ExportModel& m, const Vec3& n);

}  // namespace body::exporter
