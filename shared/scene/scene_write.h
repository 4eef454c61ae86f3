#pragma once
// scene.json out: the inverse of parse_scene (schema in shared/scene/SCENE.md).
// Only schema keys are written (a Scene holds nothing else); defaults are
// written too, so a saved file states the whole scene. Model files are written
// as `Model::file` (the text the manifest held, or what an editor set).
#include <string>

#include "shared/error.h"
#include "shared/scene/scene.h"

namespace body::scene {

// The manifest text (2-space indented JSON, newline-terminated).
std::string scene_to_json(const Scene& scene);

// Serialises, checks the text with parse_scene (resolving files against the
// target's directory, as the kiosk will) and writes it with
// write_file_atomically: an invalid scene is refused and nothing is written.
Status save_scene(const Scene& scene, const std::string& path);

}  // namespace body::scene
