#pragma once
// Model files the kiosk does not read (.stl, .ply) made into progressive meshes
// for the authoring window's Add model. The conversion is `bodygen lod` (the
// builder library's assimp import and simplification), run as a child process:
// the kiosk binary, which also ships to the Raspberry Pi, keeps no assimp, and
// the result is the same .bpm a curator would make by hand, with its levels of
// detail, written into the scene's models/ folder so that pack copies it as is.
#include <string>

#include "shared/error.h"

namespace body::kiosk::author {

// True for the extensions convert_to_bpm takes (case-insensitive).
bool needs_conversion(const std::string& file);

// Runs `bodygen lod FILE -o MODELS_DIR/STEM.bpm` (STEM-2.bpm ... when taken),
// creating MODELS_DIR, and returns the .bpm's path. bodygen is looked for next
// to the running executable, then on PATH. A failure returns bodygen's first
// error line (it names the file and why) and leaves no .bpm behind.
Result<std::string> convert_to_bpm(const std::string& file, const std::string& models_dir);

}  // namespace body::kiosk::author
