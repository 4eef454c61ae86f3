// bodygen pack scene.json -o BUNDLE/: validates a kiosk scene (schema in
// shared/scene/SCENE.md), copies its models into BUNDLE/models/ and writes
// BUNDLE/scene.json with the paths rewritten. The bundle appears atomically: it
// is built in a temporary sibling directory and renamed into place (a previous
// bundle there is replaced only after the new one is complete).
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "builder/cli/commands.h"
#include "shared/atomic_file.h"
#include "shared/cli_args.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/scene/scene.h"
#include "shared/scene/slice_volume.h"

namespace body::cli {

namespace {

namespace fs = std::filesystem;

// Checks that `m.path` is a readable model (an OBJ that parses, a .bpm the
// progressive-mesh reader accepts); the message names the manifest and JSON path.
Status check_model(const scene::Scene& s, size_t index, size_t& triangles) {
    const scene::Model& m = s.models[index];
    const std::string where = s.source + ": models[" + std::to_string(index) + "].file: '" + m.file + "'";
    std::error_code ec;
    if (!fs::is_regular_file(m.path, ec)) return input_error(where + ": no such file (" + m.path + ")");
    const std::string ext = fs::path(m.path).extension().string();
    if (ext == ".obj") {
        auto meshes = read_obj(m.path);
        if (!meshes) return input_error(where + ": " + meshes.error().message);
        triangles = 0;
        for (const Mesh& mesh : *meshes) triangles += mesh.triangle_count();
        if (triangles == 0) return input_error(where + ": no triangles");
        return ok_status();
    }
    if (ext == ".bpm") {
        // The full reader: header, every section's CRC, decodable base and splits.
        auto meshes = pm::read_bpm(m.path, pm::BpmStream::FaceOrder::Refinement);  // checked, not drawn
        if (!meshes) return input_error(where + ": " + meshes.error().message);
        triangles = 0;
        for (const auto& mesh : *meshes) triangles += mesh->max_triangle_count();
        if (triangles == 0) return input_error(where + ": no triangles");
        return ok_status();
    }
    return input_error(where + ": not a model (expected .bpm or .obj)");
}

}  // namespace

Result<PackSummary> pack_scene(const std::string& scene_path, const std::string& out) {
    auto scene = scene::read_scene(scene_path);
    if (!scene) return scene.error();
    auto text = read_file(scene_path);
    if (!text) return text.error();
    nlohmann::json manifest = nlohmann::json::parse(*text, nullptr, false);  // valid: read_scene parsed it

    // Validate every model and choose unique names inside models/.
    std::vector<std::string> names;
    std::set<std::string> used;
    PackSummary summary;
    for (size_t i = 0; i < scene->models.size(); ++i) {
        size_t triangles = 0;
        Status st = check_model(*scene, i, triangles);
        if (!st) return st.error();
        summary.triangles += triangles;
        const fs::path p(scene->models[i].path);
        std::string name = p.filename().string();
        for (int k = 2; used.count(name); ++k)
            name = p.stem().string() + "-" + std::to_string(k) + p.extension().string();
        used.insert(name);
        names.push_back(name);
        manifest["models"][i]["file"] = "models/" + name;
    }
    summary.models = scene->models.size();
    summary.groups = scene->groups.size();
    // The caps' grey-level volume is checked here and copied as slices.vol.
    std::vector<uint8_t> volume;
    if (!scene->cut_plane.volume.empty()) {
        const std::string where = scene->source + ": cut_plane.volume: '" + scene->cut_plane.volume + "'";
        auto bytes = read_file(scene->cut_plane.volume_path);
        if (!bytes) return input_error(where + ": " + bytes.error().message);
        volume.assign(bytes->begin(), bytes->end());
        if (auto v = parse_slice_volume(volume, scene->cut_plane.volume_path); !v) return v.error();
        manifest["cut_plane"]["volume"] = "slices.vol";
    }

    // Staged next to the destination so the final rename stays on one file system.
    fs::path bundle = fs::path(out).lexically_normal();
    if (bundle.filename().empty()) bundle = bundle.parent_path();
    summary.bundle = bundle.string();
    auto fill = [&](const std::string& staged_dir) -> Status {
        const fs::path staged(staged_dir);
        std::error_code ec;
        fs::create_directories(staged / "models", ec);
        if (ec) return runtime_error(bundle.string() + ": cannot create the bundle's directory: " + ec.message());
        for (size_t i = 0; i < names.size(); ++i) {
            fs::copy_file(scene->models[i].path, staged / "models" / names[i], ec);
            if (ec)
                return runtime_error(bundle.string() + ": cannot write the bundle's models/" + names[i] + ": " +
                                     ec.message());
            summary.bytes += fs::file_size(staged / "models" / names[i], ec);
        }
        if (!volume.empty()) {
            if (Status st = write_file_atomically((staged / "slices.vol").string(), volume); !st) return st.error();
            summary.bytes += volume.size();
        }
        const std::string json_text = manifest.dump(2) + "\n";
        summary.bytes += json_text.size();
        Status written = write_file_atomically(
            (staged / "scene.json").string(),
            std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(json_text.data()), json_text.size()));
        if (!written) return written.error();
        // The staged manifest must read back as the same scene.
        auto check = scene::read_scene((staged / "scene.json").string());
        if (!check) return runtime_error("pack: the written manifest does not parse: " + check.error().message);
        return ok_status();
    };
    auto replaceable = [](const std::string& dir) -> std::string {
        std::error_code ec;
        return fs::is_empty(dir, ec) || fs::exists(fs::path(dir) / "scene.json", ec)
                   ? std::string()
                   : "exists and is not a bundle (no scene.json)";
    };
    if (Status st = write_directory_atomically(bundle.string(), fill, replaceable); !st) return st.error();
    return summary;
}

int run_pack(const Args& argv) {
    auto args = CliArgs::parse(argv, {"o", "output"}, {"help", "quiet", "json"});
    if (!args) return report(args.error());
    if (args->has("help")) {
        std::printf(
            "usage: bodygen pack SCENE.json -o BUNDLE/ [--quiet] [--json]\n"
            "validates the scene (shared/scene/SCENE.md), copies its models into BUNDLE/models/ and\n"
            "writes BUNDLE/scene.json; the bundle replaces BUNDLE/ atomically. Exit 2 on a bad reference.\n"
            "  --quiet  no summary line\n"
            "  --json   the summary as JSON on stdout\n");
        return kExitOk;
    }
    const auto out = args->has("o") ? args->get("o") : args->get("output");
    if (args->positional().size() != 1 || !out)
        return report(input_error("pack: usage: bodygen pack SCENE.json -o BUNDLE/"));
    const std::string scene_path = args->positional()[0];
    auto summary = pack_scene(scene_path, *out);
    if (!summary) return report(summary.error());
    if (args->has("json")) {
        nlohmann::json j = {{"scene", scene_path},       {"bundle", summary->bundle},       {"models", summary->models},
                            {"groups", summary->groups}, {"triangles", summary->triangles}, {"bytes", summary->bytes}};
        std::printf("%s\n", j.dump(2).c_str());
    } else if (!args->has("quiet")) {
        std::printf("%s: %zu models, %zu groups, %zu triangles at full detail -> %s\n", scene_path.c_str(),
                    summary->models, summary->groups, summary->triangles, summary->bundle.c_str());
    }
    return kExitOk;
}

}  // namespace body::cli
