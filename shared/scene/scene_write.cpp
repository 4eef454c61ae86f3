// scene.json writing (contract in scene_write.h).
#include "shared/scene/scene_write.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "shared/atomic_file.h"

namespace body::scene {

namespace {

using nlohmann::ordered_json;

// The shortest decimal that reads back as the same float (0.8f is written 0.8, not 0.800000011920929).
double num(float v) {
    char buf[32];
    for (int precision = 6; precision < 9; ++precision) {
        std::snprintf(buf, sizeof buf, "%.*g", precision, static_cast<double>(v));
        if (std::strtof(buf, nullptr) == v) return std::strtod(buf, nullptr);
    }
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
    return std::strtod(buf, nullptr);
}

ordered_json vec3(const std::array<float, 3>& v) { return ordered_json::array({num(v[0]), num(v[1]), num(v[2])}); }

ordered_json lod(const Lod& l) { return l.automatic ? ordered_json("auto") : ordered_json(num(l.ratio)); }

const char* corner_name(AdminGesture::Corner c) {
    switch (c) {
        case AdminGesture::Corner::TopLeft: return "top-left";
        case AdminGesture::Corner::TopRight: return "top-right";
        case AdminGesture::Corner::BottomLeft: return "bottom-left";
        case AdminGesture::Corner::BottomRight: return "bottom-right";
    }
    return "top-left";
}

ordered_json model_json(const Model& m) {
    ordered_json j;
    j["name"] = m.name;
    j["file"] = m.file;
    if (!m.group.empty()) j["group"] = m.group;
    j["colour"] = vec3(m.colour);
    j["transform"] = {{"translate", vec3(m.transform.translate)},
                      {"rotate_deg", vec3(m.transform.rotate_deg)},
                      {"scale", num(m.transform.scale)}};
    j["style"] = style_name(m.style);
    j["lod"] = lod(m.lod);
    ordered_json label = ordered_json::object();
    for (const LabelText& t : m.labels) label[t.language] = {{"title", t.title}, {"description", t.description}};
    j["label"] = label;
    return j;
}

}  // namespace

std::string scene_to_json(const Scene& s) {
    ordered_json root;
    root["version"] = 1;
    root["models"] = ordered_json::array();
    for (const Model& m : s.models) root["models"].push_back(model_json(m));
    root["groups"] = ordered_json::array();
    for (const Group& g : s.groups) {
        ordered_json j;
        j["name"] = g.name;
        if (g.style) j["style"] = style_name(*g.style);
        if (g.lod) j["lod"] = lod(*g.lod);
        j["visible"] = g.visible;
        root["groups"].push_back(j);
    }
    const HomeCamera& c = s.camera;
    root["camera"] = {{"target", vec3(c.target)},
                      {"azimuth_deg", num(c.azimuth_deg)},
                      {"polar_deg", num(c.polar_deg)},
                      {"distance", num(c.distance)},
                      {"fov_deg", num(c.fov_deg)}};
    const KioskSettings& k = s.kiosk;
    root["kiosk"] = {{"idle_seconds", num(k.idle_seconds)},
                     {"reset_seconds", num(k.reset_seconds)},
                     {"languages", k.languages},
                     {"admin_gesture",
                      {{"corner", corner_name(k.admin.corner)},
                       {"taps", k.admin.taps},
                       {"seconds", num(k.admin.seconds)},
                       {"corner_size", num(k.admin.corner_size)}}},
                     {"frame_ms_target", num(k.frame_ms_target)}};
    return root.dump(2) + "\n";
}

Status save_scene(const Scene& scene, const std::string& path) {
    const std::string text = scene_to_json(scene);
    // The kiosk resolves files against the manifest's directory: check them the same way.
    auto check = parse_scene(text, path, std::filesystem::path(path).parent_path().string());
    if (!check) return check.error();
    return write_file_atomically(path,
                                 std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
}

}  // namespace body::scene
