// bodygen exhibit INPUT... -o BUNDLE/: from what users have (label volumes with
// their tables, RT-STRUCTs, contour stacks, meshes) to a validated kiosk bundle
// in one command: import -> build (per structure) -> progressive meshes ->
// scene.json -> pack. The stages are the library's (builder/exhibit/exhibit.h);
// options keep the per-step commands' names. A structure that fails is reported
// and left out (exit 0 with the count; 1 when none built; --strict: any fails).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "builder/cli/commands.h"
#include "builder/exhibit/exhibit.h"
#include "builder/exhibit/slices_volume.h"
#ifdef BODY_WITH_IMPORT
#include "builder/import/grey_volume.h"
#include "builder/import/import.h"
#endif
#include "builder/mesh_import/mesh_import.h"
#include "shared/atomic_file.h"
#include "shared/cli_args.h"
#include "shared/input_file.h"

namespace body::cli {

Result<BuildOptions> build_options_from_args(const CliArgs& args);   // cmd_build.cpp
Result<lod::LodOptions> lod_options_from_args(const CliArgs& args);  // cmd_lod.cpp
#ifdef BODY_WITH_IMPORT
Result<ImportOptions> import_options_from_args(const CliArgs& args);  // cmd_contours.cpp
#endif

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage =
    "usage: bodygen exhibit INPUT... -o BUNDLE/ [options]\n"
    "  INPUT: a NIfTI label volume (.nii/.nii.gz; its label/colour table beside it or --labels),\n"
    "         a DICOM RT-STRUCT (.dcm), a contour stack (.contours.json), an OBJ file\n"
    "         (one model per object), a VRML97 .wrl (one model per Shape, its colour kept),\n"
    "         an STL/PLY/glTF file or a directory of mesh files;\n"
    "         several may be given\n"
    "  --groups FILE        group pattern table: PATTERN<TAB>GROUP lines, shell globs on the\n"
    "                       structure names, first match wins, {side} becomes left/right\n"
    "                       (example: builder/import/aal_groups.tsv)\n"
    "  --translations FILE  NAME<TAB>LANG<TAB>TITLE<TAB>DESCRIPTION rows: labels in more languages\n"
    "  --view anterior|left|posterior|right   the camera's start, head up (default anterior)\n"
    "  --orientation XYZ    patient directions of +x,+y,+z for inputs that do not say (contour\n"
    "                       stacks, meshes): e.g. RAS (default), LPS; volumes and RT-STRUCTs\n"
    "                       bring their own\n"
    "  --jobs N             structures built on N threads (default 1)\n"
    "  --strict             fail (and write nothing) when any structure fails\n"
    "  --quiet              no progress bar, warnings or summary\n"
    "  --json               the summary as JSON on stdout\n"
    "  build options:  --caps --tiling --correspondence --branching --smooth --interpolate --ring-tolerance\n"
    "                  --ring-voxel (bodygen build --help)\n"
    "  lod options:    --min-triangles --chunk-splits --no-normals (bodygen lod --help)\n"
#ifdef BODY_WITH_IMPORT
    "  --slices-volume GREY.nii  a grey-level NIfTI image (e.g. the template the labels were drawn\n"
    "                       on) shown on the kiosk's cut-plane caps: written as slices.vol, windowed\n"
    "                       to its 0.5-99.5th percentiles, placed as the models are\n"
    "  import options: --labels --axis --step --only --threshold --tolerance --min-area --label-smooth\n"
    "                  (bodygen contours --help)\n"
#endif
    "colours: the source's (RT-STRUCT ROI colours, colour tables beside label volumes), else\n"
    "distinct colours with touching structures apart.\n";

bool is_mesh_file(const fs::path& p) { return body::is_mesh_file(p.string()); }

// The parts of one mesh file: a one-mesh file is named after the file.
Result<std::vector<exhibit::Part>> mesh_parts(const std::string& path, const std::array<Vec3, 3>& axes) {
    auto meshes = read_mesh_file(path);
    if (!meshes) return meshes.error();
    if (meshes->size() == 1) (*meshes)[0].name = fs::path(path).stem().string();
    return exhibit::parts_from_meshes(std::move(*meshes), path, axes);
}

Result<std::vector<exhibit::Part>> load_parts(const CliArgs& args, const std::array<Vec3, 3>& axes, bool quiet) {
    std::vector<exhibit::Part> parts;
    auto add = [&](Result<std::vector<exhibit::Part>> more) -> Status {
        if (!more) return more.error();
        for (auto& p : *more) parts.push_back(std::move(p));
        return ok_status();
    };
    for (const std::string& input : args.positional()) {
        std::error_code ec;
        if (fs::is_directory(input, ec)) {
            std::vector<fs::path> files;
            for (const auto& e : fs::directory_iterator(input, ec))
                if (e.is_regular_file() && is_mesh_file(e.path())) files.push_back(e.path());
            std::sort(files.begin(), files.end());
            if (files.empty())
                return input_error(input + ": no mesh files (.obj, .wrl, .stl, .ply, .gltf, .glb) in the directory");
            for (const fs::path& f : files)
                if (Status st = add(mesh_parts(f.string(), axes)); !st) return st.error();
            continue;
        }
        if (is_mesh_file(input)) {
            if (Status st = add(mesh_parts(input, axes)); !st) return st.error();
            continue;
        }
#ifdef BODY_WITH_IMPORT
        auto import = import_options_from_args(args);
        if (!import) return import.error();
        if (!quiet) import->note = [](const std::string& m) { std::fprintf(stderr, "bodygen: note: %s\n", m.c_str());
    };
    auto stack = load_any_contour_source(input, *import);
#else
        (void)quiet;
        auto stack = read_contour_stack(input);
#endif
    if (!stack) return stack.error();
    if (Status st = add(exhibit::parts_from_stack(*stack, input, axes)); !st) return st.error();
}
if (parts.empty()) return input_error("exhibit: no structures in the inputs");
return parts;
}  // namespace

Result<exhibit::SceneOptions> scene_options_from_args(const CliArgs& args) {
    exhibit::SceneOptions o;
    auto view = exhibit::parse_view(args.get_or("view", "anterior"));
    if (!view) return view.error();
    o.view = *view;
    if (auto g = args.get("groups")) {
        auto t = exhibit::read_group_table(*g);
        if (!t) return t.error();
        o.groups = std::move(*t);
    }
    if (auto tr = args.get("translations")) {
        auto t = exhibit::read_translations(*tr);
        if (!t) return t.error();
        o.translations = std::move(*t);
    }
    return o;
}

// Writes the built parts and the manifest into `work` (models/ + scene.json).
// With `volume`, also slices.vol (shared/scene/slice_volume.h) named by cut_plane.volume.
Status write_sources(const fs::path& work, const std::vector<exhibit::Part>& parts,
                     const std::vector<exhibit::BuiltPart>& built, const exhibit::SceneOptions& options,
                     const SliceVolume* volume) {
    std::error_code ec;
    fs::create_directories(work / "models", ec);
    if (ec) return runtime_error(work.string() + ": cannot create: " + ec.message());
    const std::vector<std::string> stems = exhibit::model_stems(parts);
    std::vector<std::string> files(parts.size());
    for (size_t i = 0; i < parts.size(); ++i) {
        if (built[i].bpm.empty()) continue;
        files[i] = "models/" + stems[i] + ".bpm";
        Status st = write_file_atomically((work / files[i]).string(), built[i].bpm);
        if (!st) return st;
    }
    nlohmann::json scene = exhibit::scene_for(parts, built, files, options);
    if (volume) {
        if (Status st = write_file_atomically((work / "slices.vol").string(), slice_volume_bytes(*volume)); !st)
            return st;
        scene["cut_plane"]["volume"] = "slices.vol";
    }
    const std::string text = scene.dump(1) + "\n";
    return write_file_atomically((work / "scene.json").string(),
                                 std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

void print_json(const std::vector<exhibit::Part>& parts, const std::vector<exhibit::BuiltPart>& built,
                const PackSummary& pack, double seconds) {
    nlohmann::json failed = nlohmann::json::array();
    for (size_t i = 0; i < parts.size(); ++i)
        if (built[i].error)
            failed.push_back(
                {{"name", parts[i].name}, {"source", parts[i].source}, {"reason", built[i].error->message}});
    nlohmann::json j = {
        {"bundle", pack.bundle}, {"models", pack.models},      {"groups", pack.groups}, {"triangles", pack.triangles},
        {"bytes", pack.bytes},   {"structures", parts.size()}, {"failed", failed},      {"seconds", seconds}};
    std::printf("%s\n", j.dump(2).c_str());
}

}  // namespace body::cli

int run_exhibit(const Args& argv) {
    auto args = CliArgs::parse(
        argv,
        {"output",         "groups",       "translations",   "view",         "orientation", "jobs",
         "caps",           "tiling",       "correspondence", "branching",    "smooth",      "interpolate",
         "ring-tolerance", "ring-voxel",   "min-triangles",  "chunk-splits",
#ifdef BODY_WITH_IMPORT
         "labels",         "axis",         "step",           "only",         "threshold",   "tolerance",
         "min-area",       "label-smooth", "slices-volume"
#endif
        },
        {"help", "quiet", "json", "strict", "no-normals"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf("%s", kUsage);
        return kExitOk;
    }
    if (args->positional().empty()) return report(input_error("exhibit: expected at least one INPUT (see --help)"));
    if (!args->has("output")) return report(input_error("exhibit: missing -o BUNDLE/"));
    const bool quiet = args->has("quiet"), json_out = args->has("json");
    exhibit::PartOptions options;
    auto build = build_options_from_args(*args);
    if (!build) return report(build.error());
    options.build = std::move(*build);
    options.jobs = options.build.jobs;
    auto lod = lod_options_from_args(*args);
    if (!lod) return report(lod.error());
    options.lod = *lod;
    auto scene_options = scene_options_from_args(*args);
    if (!scene_options) return report(scene_options.error());
    auto axes = exhibit::parse_orientation(args->get_or("orientation", "RAS"));
    if (!axes) return report(axes.error());

    const auto start = std::chrono::steady_clock::now();
#ifdef BODY_WITH_IMPORT
    std::optional<GreyImage> grey;  // read first: a bad image writes nothing
    if (auto g = args->get("slices-volume")) {
        auto image = read_grey_image(*g);
        if (!image) return report(image.error());
        grey = std::move(*image);
    }
#endif
    auto parts = load_parts(*args, *axes, quiet);
    if (!parts) return report(parts.error());
    if (!quiet && ::isatty(STDERR_FILENO)) options.progress = progress_bar("structures");
    const std::vector<exhibit::BuiltPart> built = exhibit::build_parts(*parts, options);

    size_t failures = 0;
    const Error* first_failure = nullptr;
    for (size_t i = 0; i < parts->size(); ++i) {
        if (!quiet)
            for (const std::string& w : built[i].warnings) std::fprintf(stderr, "bodygen: warning: %s\n", w.c_str());
        if (!built[i].error) continue;
        if (!first_failure) first_failure = &*built[i].error;
        ++failures;
        if (!quiet)
            std::fprintf(stderr, "bodygen: left out %s: %s\n", (*parts)[i].name.c_str(),
                         built[i].error->message.c_str());
    }
    if (failures == parts->size())
        return report(runtime_error("exhibit: no structure built (" + std::to_string(failures) + " failed)"));
    if (failures > 0 && args->has("strict")) {
        std::fprintf(stderr, "bodygen: exhibit: --strict: %zu of %zu structures failed; nothing written\n", failures,
                     parts->size());
        return first_failure->exit_code;
    }

    fs::path bundle = fs::path(*args->get("output")).lexically_normal();
    if (bundle.filename().empty()) bundle = bundle.parent_path();
    if (Status apart = check_output_apart(bundle.string() + "/", args->positional()); !apart)
        return report(apart.error());
    // This run's sources, "BUNDLE.work.tmp-PID": removed on a signal, swept after a kill.
    const ScratchPath scratch(bundle.string() + ".work");
    const fs::path work = scratch.path();
    std::optional<SliceVolume> volume;
#ifdef BODY_WITH_IMPORT
    if (grey) {
        auto v = exhibit::slices_volume(grey->dim, grey->values, grey->affine,
                                        exhibit::volume_axes(*parts, built, *axes), *args->get("slices-volume"));
        if (!v) return report(v.error());
        volume = std::move(*v);
    }
#endif
    Status st = write_sources(work, *parts, built, *scene_options, volume ? &*volume : nullptr);
    // The sources are this run's scratch: a failure there names the bundle asked for.
    if (!st)
        st = Error{bundle.string() + "/: " + renamed_in_message(st.error().message, work.string(), bundle.string()),
                   st.error().exit_code};
    Result<PackSummary> pack = st ? pack_scene((work / "scene.json").string(), bundle.string()) : st.error();
    if (!pack) return report(pack.error());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (json_out) print_json(*parts, built, *pack, seconds);
    if (!quiet)
        std::fprintf(stderr, "exhibit: %zu of %zu structures, %zu groups -> %s (%zu bytes, %zu left out) in %.2f s\n",
                     pack->models, parts->size(), pack->groups, pack->bundle.c_str(), pack->bytes, failures, seconds);
    return kExitOk;
}

}  // namespace body::cli
