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

// language -> {"title", "description"} (labels, pins).
ordered_json label_json(const std::vector<LabelText>& texts) {
    ordered_json j = ordered_json::object();
    for (const LabelText& t : texts) j[t.language] = {{"title", t.title}, {"description", t.description}};
    return j;
}

// language -> text (tour titles, step captions: the parser reads no description there).
ordered_json text_json(const std::vector<LabelText>& texts) {
    ordered_json j = ordered_json::object();
    for (const LabelText& t : texts) j[t.language] = t.title;
    return j;
}

const char* easing_name(Easing e) {
    switch (e) {
        case Easing::Linear: return "linear";
        case Easing::EaseIn: return "ease-in";
        case Easing::EaseOut: return "ease-out";
        case Easing::EaseInOut: return "ease-in-out";
    }
    return "ease-in-out";
}

// Optional step values are written only when set: a missing one means "keep the previous step's".
ordered_json step_json(const TourStep& st) {
    ordered_json j = ordered_json::object();
    const TourCamera& c = st.camera;
    if (c.target || c.azimuth_deg || c.polar_deg || c.distance) {
        ordered_json cam = ordered_json::object();
        if (c.target) cam["target"] = vec3(*c.target);
        if (c.azimuth_deg) cam["azimuth_deg"] = num(*c.azimuth_deg);
        if (c.polar_deg) cam["polar_deg"] = num(*c.polar_deg);
        if (c.distance) cam["distance"] = num(*c.distance);
        j["camera"] = cam;
    }
    if (st.visible) j["visible"] = *st.visible;
    if (!st.styles.empty()) {
        ordered_json styles = ordered_json::object();
        for (const auto& [name, style] : st.styles) styles[name] = style_name(style);
        j["styles"] = styles;
    }
    if (!st.select.empty()) j["select"] = st.select;
    if (!st.caption.empty()) j["caption"] = text_json(st.caption);
    j["duration"] = num(st.duration);
    j["hold"] = num(st.hold);
    j["easing"] = easing_name(st.easing);
    if (st.cut) {
        static const char* const kAxes[] = {"axial", "coronal", "sagittal"};
        ordered_json cut = ordered_json::object();
        if (st.cut->axis >= 0 && st.cut->axis < 3)
            cut["axis"] = kAxes[st.cut->axis];
        else
            cut["normal"] = vec3(st.cut->normal);
        cut["offset"] = num(st.cut->offset);
        j["cut"] = cut;
    }
    return j;
}

ordered_json tour_json(const Tour& t) {
    ordered_json j;
    j["name"] = t.name;
    if (!t.title.empty()) j["title"] = text_json(t.title);
    j["steps"] = ordered_json::array();
    for (const TourStep& st : t.steps) j["steps"].push_back(step_json(st));
    return j;
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
    j["label"] = label_json(m.labels);
    if (!m.pins.empty()) {
        j["pins"] = ordered_json::array();
        for (const Pin& p : m.pins) j["pins"].push_back({{"anchor", vec3(p.anchor)}, {"label", label_json(p.labels)}});
    }
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
    if (!k.attract_tour.empty()) root["kiosk"]["attract_tour"] = k.attract_tour;
    root["kiosk"]["countdown_seconds"] = num(k.countdown_seconds);
    root["kiosk"]["pins"] = k.pins;
    if (!k.operator_pin.empty()) root["kiosk"]["operator_pin"] = k.operator_pin;
    // The access modes only when on: scenes that do not use them save as before.
    for (const auto& [key, on] : {std::pair{"high_contrast", k.high_contrast}, std::pair{"large_text", k.large_text},
                                  std::pair{"access_buttons", k.access_buttons}, std::pair{"icons", k.icons}})
        if (on) root["kiosk"][key] = true;
    static const char* const kCutPresets[] = {"axial", "coronal", "sagittal"};
    for (size_t i = 0; i < 3; ++i)
        if (const auto& n = s.cut_plane.axes[i]) root["cut_plane"][kCutPresets[i]] = vec3(*n);
    if (s.cut_plane.slice_normal) root["cut_plane"]["slice_normal"] = vec3(*s.cut_plane.slice_normal);
    if (!s.cut_plane.volume.empty()) root["cut_plane"]["volume"] = s.cut_plane.volume;
    if (s.cut_plane.volume_around) root["cut_plane"]["volume_around"] = true;
    if (!s.cut_plane.slices.empty()) {
        root["cut_plane"]["slices"] = ordered_json::array();
        for (float a : s.cut_plane.slices) root["cut_plane"]["slices"].push_back(num(a));
    }
    if (!s.tours.empty()) {
        root["tours"] = ordered_json::array();
        for (const Tour& t : s.tours) root["tours"].push_back(tour_json(t));
    }
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
