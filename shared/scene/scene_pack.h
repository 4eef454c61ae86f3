#pragma once
// Packing a kiosk scene into a bundle (`bodygen pack`, `bodygen exhibit` and the
// authoring window's Pack): validates the scene (shared/scene/SCENE.md) and every
// model file it names (an OBJ that parses, a .bpm the full reader accepts),
// copies the models into BUNDLE/models/ (unique names) and writes
// BUNDLE/scene.json with the paths rewritten. The bundle appears atomically: it
// is built in a temporary sibling directory and renamed into place (a previous
// bundle there is replaced only after the new one is complete). A bad
// reference fails with the manifest, the JSON path and the reason, and leaves
// nothing behind.
#include <cstddef>
#include <string>

#include "shared/error.h"

namespace body::scene {

// `bytes` is the bundle's size; `triangles` the models' at full detail.
struct PackSummary {
    std::string bundle;
    size_t models = 0, groups = 0, triangles = 0, bytes = 0;
};
Result<PackSummary> pack_scene(const std::string& scene_path, const std::string& bundle);

}  // namespace body::scene
