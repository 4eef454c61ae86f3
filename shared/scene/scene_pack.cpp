// A scene packed into a bundle (contract in scene_pack.h).
#include "shared/scene/scene_pack.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <span>

#include "shared/atomic_file.h"
#include "shared/input_file.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/scene/scene.h"
#include "shared/scene/slice_volume.h"

namespace body::scene {

namespace {

namespace fs = std::filesystem;

// Checks that `m.path` is a readable model (an OBJ that parses, a .bpm the
// progressive-mesh reader accepts); the message names the manifest and JSON path.
Status check_model(const Scene& s, size_t index, size_t& triangles) {
    const Model& m = s.models[index];
    const std::string where = s.source + ": models[" + std::to_string(index) + "].file: '" + m.file + "'";
    // A FIFO, directory or device is named as such (and never opened).
    if (Status regular = check_regular_file(m.path); !regular) {
        const std::string& message = regular.error().message;  // "PATH: reason"
        const std::string reason = message.starts_with(m.path + ": ") ? message.substr(m.path.size() + 2) : message;
        return input_error(where + ": " + reason + " (" + m.path + ")");
    }
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
    auto scene = read_scene(scene_path);
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
    // The bundle replaces its directory whole: never one holding the scene or a model.
    std::vector<std::string> sources{scene_path};
    for (const scene::Model& m : scene->models) sources.push_back(m.path);
    if (Status apart = check_output_apart(bundle.string() + "/", sources); !apart) return apart.error();
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
        auto check = read_scene((staged / "scene.json").string());
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

}  // namespace body::scene
