#pragma once
// An exhibit: many structures from one or more sources -> one progressive mesh
// file each and a scene manifest (shared/scene/SCENE.md) that `bodygen pack`
// turns into a kiosk bundle. `bodygen exhibit` (builder/cli/cmd_exhibit.cpp)
// drives it; the stages are the library's own (build_structures, encode_bpm).
//
// Contract:
// - One Part per structure: a label-volume/RT-STRUCT/stack structure (built
//   from its own contours, so one structure's failure leaves the others
//   alone), or a finished mesh (one per OBJ object).
// - build_parts() runs the parts on `jobs` threads; the result does not depend
//   on `jobs`. A part that fails keeps its reason and no bytes.
// - scene_for() names models by unique file-safe ids, takes colours from the
//   source or assign_colours() (palette.h), titles from names.h and the
//   translations, groups from the group table, rotates every model from its
//   source's patient orientation to the kiosk's (orientation.h) and points the
//   camera at the chosen anatomical view; the contour-built parts' slice
//   planes become cut_plane.slices (the kiosk's cut plane snaps to them).
#include <array>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/exhibit/group_table.h"
#include "builder/exhibit/orientation.h"
#include "builder/exhibit/translations.h"
#include "builder/lod/simplify.h"
#include "builder/pipeline/build_pipeline.h"
#include "shared/error.h"
#include "shared/mesh.h"

namespace body::exhibit {

struct Part {
    std::string name;                      // as the source spells it
    std::string source;                    // file it came from (messages)
    std::optional<Vec3> colour;            // from the source, when it has one
    std::array<Vec3, 3> ras_axes;          // the data's +x, +y, +z in RAS+ (orientation.h)
    std::optional<ContourStack> contours;  // this structure's contours, or
    std::optional<Mesh> mesh;              // a finished mesh
};

// One part per structure of `stack` (empty slices inside a structure's range are
// kept: a gap is capped, not bridged). Stacks without an orientation get
// `fallback_axes`. A colour equal to the stack format's default grey, or black
// (what display tables leave unset labels), counts as none.
std::vector<Part> parts_from_stack(const ContourStack& stack, const std::string& source,
                                   const std::array<Vec3, 3>& fallback_axes);
// One part per mesh; mesh.color is the part's colour unless it is the default grey or
// black (readers leave the grey where the file has none: OBJ, STL, PLY, glTF).
std::vector<Part> parts_from_meshes(std::vector<Mesh> meshes, const std::string& source,
                                    const std::array<Vec3, 3>& axes);

struct PartOptions {
    BuildOptions build;  // `jobs`, `progress` unused (parts run in parallel instead)
    lod::LodOptions lod;
    unsigned jobs = 1;
    // Called after each part, from the worker threads, one call at a time.
    std::function<void(size_t done, size_t total)> progress;
};

struct BuiltPart {
    std::vector<uint8_t> bpm;  // empty when the part failed
    std::optional<Error> error;
    std::vector<std::string> warnings;
    Vec3 lo{0.0}, hi{0.0};  // bounds in the kiosk frame (colour neighbours)
    size_t triangles = 0;
    bool closed_manifold = false;
    double seconds = 0.0;
};

std::vector<BuiltPart> build_parts(const std::vector<Part>& parts, const PartOptions& options);

struct SceneOptions {
    View view = View::Anterior;
    std::optional<GroupTable> groups;
    std::optional<Translations> translations;
};

// The manifest for the parts that built; `files[i]` is part i's model file
// relative to the manifest ("" for a failed part).
nlohmann::json scene_for(const std::vector<Part>& parts, const std::vector<BuiltPart>& built,
                         const std::vector<std::string>& files, const SceneOptions& options);

// A file-safe, unique stem per part (from its name).
std::vector<std::string> model_stems(const std::vector<Part>& parts);

}  // namespace body::exhibit
