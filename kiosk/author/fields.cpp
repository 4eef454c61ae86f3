// The editors of scene.json's keys (contract in fields.h). Ranges are the
// parser's: a value out of range is refused when the document validates.
#include "kiosk/author/fields.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "kiosk/author/fields_detail.h"

namespace body::kiosk::author {

namespace detail {

using scene::Scene;

std::string fmt(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
    return buf;
}

std::string fmt3(const std::array<float, 3>& v) { return fmt(v[0]) + " " + fmt(v[1]) + " " + fmt(v[2]); }

Status parse_number(const std::string& text, const char* what, float& out) {
    char* end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    while (end && (*end == ' ' || *end == '\t')) ++end;
    if (text.empty() || !end || *end != '\0')
        return input_error(std::string(what) + ": '" + text + "' is not a number");
    out = v;
    return ok_status();
}

Status parse_vec3(const std::string& text, const char* what, std::array<float, 3>& out) {
    std::istringstream in(text);
    std::array<std::string, 3> parts;
    std::string extra;
    if (!(in >> parts[0] >> parts[1] >> parts[2]) || (in >> extra))
        return input_error(std::string(what) + ": expected three numbers \"x y z\"");
    std::array<float, 3> v{};
    for (int i = 0; i < 3; ++i)
        if (auto s = parse_number(parts[static_cast<size_t>(i)], what, v[static_cast<size_t>(i)]); !s) return s;
    out = v;
    return ok_status();
}

Status parse_lod(const std::string& text, const char* what, scene::Lod& out) {
    if (text == "auto") {
        out = scene::Lod{};
        return ok_status();
    }
    float r = 0;
    if (auto s = parse_number(text, what, r); !s)
        return input_error(std::string(what) + ": \"auto\" or a ratio in (0, 1]");
    out = scene::Lod{false, r};
    return ok_status();
}

std::string lod_text(const scene::Lod& l) { return l.automatic ? "auto" : fmt(l.ratio); }

Status parse_style_text(const std::string& text, const char* what, Style& out) {
    auto s = parse_style(text);
    if (!s) return input_error(std::string(what) + ": unknown style '" + text + "'");
    out = *s;
    return ok_status();
}

std::vector<std::string> style_choices(const Scene&) {
    return {"smooth", "wireframe", "lines", "hatching", "hatching-2tone"};
}
std::vector<std::string> bool_choices(const Scene&) { return {"true", "false"}; }

}  // namespace detail

namespace {

using scene::Scene;
using namespace detail;

std::vector<std::string> optional_style_choices(const Scene& s) {
    auto c = style_choices(s);
    c.insert(c.begin(), "none");
    return c;
}
std::vector<std::string> model_lod_choices(const Scene&) { return {"auto", "1", "0.5", "0.25", "0.1"}; }
std::vector<std::string> group_lod_choices(const Scene&) { return {"none", "auto", "1", "0.5", "0.25", "0.1"}; }
std::vector<std::string> group_choices(const Scene& s) {
    std::vector<std::string> c{"none"};
    for (const scene::Group& g : s.groups) c.push_back(g.name);
    return c;
}
std::vector<std::string> corner_choices(const Scene&) {
    return {"top-left", "top-right", "bottom-left", "bottom-right"};
}

scene::Model& model(Scene& s, const FieldTarget& t) { return s.models.at(static_cast<size_t>(t.model)); }
const scene::Model& model(const Scene& s, const FieldTarget& t) { return s.models.at(static_cast<size_t>(t.model)); }
scene::Group& group(Scene& s, const FieldTarget& t) { return s.groups.at(static_cast<size_t>(t.group)); }
const scene::Group& group(const Scene& s, const FieldTarget& t) { return s.groups.at(static_cast<size_t>(t.group)); }

// The label in the target's language, created (titled as the default language's) when absent.
scene::LabelText& label(Scene& s, const FieldTarget& t) {
    scene::Model& m = model(s, t);
    for (scene::LabelText& l : m.labels)
        if (l.language == t.language) return l;
    m.labels.push_back(scene::LabelText{t.language, s.label(m, t.language).title, ""});
    return m.labels.back();
}

const scene::LabelText* find_label(const Scene& s, const FieldTarget& t) {
    for (const scene::LabelText& l : model(s, t).labels)
        if (l.language == t.language) return &l;
    return nullptr;
}

const char* corner_text(scene::AdminGesture::Corner c) {
    static const char* const names[] = {"top-left", "top-right", "bottom-left", "bottom-right"};
    return names[static_cast<size_t>(c)];
}

std::vector<Field> model_fields() {
    return {
        {"models[].name", "name", FieldScope::Model, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return model(s, t).name; },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             rename_in_tours(s, model(s, t).name, v);  // steps naming it follow the rename
             model(s, t).name = v;
             return ok_status();
         }},
        {"models[].file", "file", FieldScope::Model, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return model(s, t).file; },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             scene::Model& m = model(s, t);
             m.file = v;
             std::filesystem::path f(v);
             m.path = f.is_absolute() || s.base_dir.empty() ? v : (std::filesystem::path(s.base_dir) / f).string();
             return ok_status();
         }},
        {"models[].group", "group", FieldScope::Model, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) {
             const std::string& g = model(s, t).group;
             return g.empty() ? std::string("none") : g;
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             model(s, t).group = v == "none" ? std::string() : v;
             return ok_status();
         },
         group_choices},
        {"models[].colour", "colour", FieldScope::Model, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget& t) { return fmt3(model(s, t).colour); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_vec3(v, "colour", model(s, t).colour);
         }},
        {"models[].transform", "translate", FieldScope::Model, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget& t) { return fmt3(model(s, t).transform.translate); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_vec3(v, "translate", model(s, t).transform.translate);
         }},
        {"models[].transform", "rotate (deg)", FieldScope::Model, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget& t) { return fmt3(model(s, t).transform.rotate_deg); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_vec3(v, "rotate", model(s, t).transform.rotate_deg);
         }},
        {"models[].transform", "scale", FieldScope::Model, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return fmt(model(s, t).transform.scale); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_number(v, "scale", model(s, t).transform.scale);
         }},
        {"models[].style", "style", FieldScope::Model, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) { return std::string(style_name(model(s, t).style)); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_style_text(v, "style", model(s, t).style);
         },
         style_choices},
        {"models[].lod", "LOD", FieldScope::Model, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) { return lod_text(model(s, t).lod); },
         [](Scene& s, const FieldTarget& t, const std::string& v) { return parse_lod(v, "LOD", model(s, t).lod); },
         model_lod_choices},
        {"models[].label", "title", FieldScope::Label, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) {
             const scene::LabelText* l = find_label(s, t);
             return l ? l->title : std::string();
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             label(s, t).title = v;
             return ok_status();
         }},
        {"models[].label", "description", FieldScope::Label, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) {
             const scene::LabelText* l = find_label(s, t);
             return l ? l->description : std::string();
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             label(s, t).description = v;
             return ok_status();
         }},
    };
}

std::vector<Field> group_fields() {
    return {
        {"groups[].name", "name", FieldScope::Group, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return group(s, t).name; },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             const std::string old = group(s, t).name;
             for (scene::Model& m : s.models)
                 if (m.group == old) m.group = v;  // members follow the rename
             rename_in_tours(s, old, v);
             group(s, t).name = v;
             return ok_status();
         }},
        {"groups[].style", "style", FieldScope::Group, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) {
             const auto& st = group(s, t).style;
             return st ? std::string(style_name(*st)) : std::string("none");
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             if (v == "none") {
                 group(s, t).style.reset();
                 return ok_status();
             }
             Style st{};
             if (auto r = parse_style_text(v, "style", st); !r) return r;
             group(s, t).style = st;
             return ok_status();
         },
         optional_style_choices},
        {"groups[].lod", "LOD", FieldScope::Group, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) {
             const auto& l = group(s, t).lod;
             return l ? lod_text(*l) : std::string("none");
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             if (v == "none") {
                 group(s, t).lod.reset();
                 return ok_status();
             }
             scene::Lod l;
             if (auto r = parse_lod(v, "LOD", l); !r) return r;
             group(s, t).lod = l;
             return ok_status();
         },
         group_lod_choices},
        {"groups[].visible", "visible", FieldScope::Group, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) { return std::string(group(s, t).visible ? "true" : "false"); },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             if (v != "true" && v != "false") return input_error("visible: true or false");
             group(s, t).visible = v == "true";
             return ok_status();
         },
         bool_choices},
    };
}

std::vector<Field> camera_fields() {
    return {
        {"camera.target", "camera target", FieldScope::Scene, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget&) { return fmt3(s.camera.target); },
         [](Scene& s, const FieldTarget&, const std::string& v) { return parse_vec3(v, "target", s.camera.target); }},
        {"camera.azimuth_deg", "camera azimuth", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.camera.azimuth_deg); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "azimuth", s.camera.azimuth_deg);
         }},
        {"camera.polar_deg", "camera polar", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.camera.polar_deg); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "polar", s.camera.polar_deg);
         }},
        {"camera.distance", "camera distance", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.camera.distance); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "distance", s.camera.distance);
         }},
        {"camera.fov_deg", "camera fov", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.camera.fov_deg); },
         [](Scene& s, const FieldTarget&, const std::string& v) { return parse_number(v, "fov", s.camera.fov_deg); }},
    };
}

// Languages as "en de": labels in a language no longer listed go (undo brings them back);
// a model left without any gets its name as the title in the first language.
Status set_languages(Scene& s, const FieldTarget&, const std::string& v) {
    std::istringstream in(v);
    std::vector<std::string> langs;
    for (std::string w; in >> w;) langs.push_back(w);
    if (langs.empty()) return input_error("languages: at least one, e.g. \"en de\"");
    s.kiosk.languages = langs;
    for (scene::Model& m : s.models) {
        std::erase_if(m.labels, [&](const scene::LabelText& l) {
            return std::find(langs.begin(), langs.end(), l.language) == langs.end();
        });
        if (m.labels.empty()) m.labels.push_back(scene::LabelText{langs.front(), m.name, ""});
    }
    drop_tour_languages(s, langs);
    return ok_status();
}

std::vector<Field> kiosk_fields() {
    return {
        {"kiosk.idle_seconds", "idle (s)", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.idle_seconds); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "idle", s.kiosk.idle_seconds);
         }},
        {"kiosk.reset_seconds", "reset (s)", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.reset_seconds); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "reset", s.kiosk.reset_seconds);
         }},
        {"kiosk.languages", "languages", FieldScope::Scene, FieldKind::Text,
         [](const Scene& s, const FieldTarget&) {
             std::string out;
             for (const std::string& l : s.kiosk.languages) out += (out.empty() ? "" : " ") + l;
             return out;
         },
         set_languages},
        {"kiosk.admin_gesture", "admin corner", FieldScope::Scene, FieldKind::Choice,
         [](const Scene& s, const FieldTarget&) { return std::string(corner_text(s.kiosk.admin.corner)); },
         [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
             const auto c = corner_choices(s);
             const auto it = std::find(c.begin(), c.end(), v);
             if (it == c.end()) return input_error("admin corner: top-left, top-right, bottom-left or bottom-right");
             s.kiosk.admin.corner = static_cast<scene::AdminGesture::Corner>(it - c.begin());
             return ok_status();
         },
         corner_choices},
        {"kiosk.admin_gesture", "admin taps", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return std::to_string(s.kiosk.admin.taps); },
         [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
             float f = 0;
             if (auto r = parse_number(v, "admin taps", f); !r) return r;
             if (f != static_cast<float>(static_cast<int>(f))) return input_error("admin taps: a whole number");
             s.kiosk.admin.taps = static_cast<int>(f);
             return ok_status();
         }},
        {"kiosk.admin_gesture", "admin seconds", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.admin.seconds); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "admin seconds", s.kiosk.admin.seconds);
         }},
        {"kiosk.admin_gesture", "admin corner size", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.admin.corner_size); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "admin corner size", s.kiosk.admin.corner_size);
         }},
        {"kiosk.frame_ms_target", "frame target (ms)", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.frame_ms_target); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "frame target", s.kiosk.frame_ms_target);
         }},
    };
}

// The snapping slices' normal (scene.h CutPlaneSettings): empty text unsets it.
Field cut_slice_normal_field() {
    return {"cut_plane.slice_normal",
            "cut slice normal",
            FieldScope::Scene,
            FieldKind::Vec3,
            [](const Scene& s, const FieldTarget&) {
                return s.cut_plane.slice_normal ? fmt3(*s.cut_plane.slice_normal) : std::string();
            },
            [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
                if (v.find_first_not_of(" \t") == std::string::npos) {
                    s.cut_plane.slice_normal.reset();
                    return ok_status();
                }
                std::array<float, 3> n{};
                if (auto r = parse_vec3(v, "cut slice normal", n); !r) return r;
                if (n[0] == 0.0f && n[1] == 0.0f && n[2] == 0.0f) return input_error("cut slice normal: not all 0");
                s.cut_plane.slice_normal = n;
                return ok_status();
            }};
}

// The snapping slices' positions, numbers apart by spaces.
Field cut_slices_field() {
    return {"cut_plane.slices",
            "cut slices",
            FieldScope::Scene,
            FieldKind::Text,
            [](const Scene& s, const FieldTarget&) {
                std::string out;
                for (float a : s.cut_plane.slices) {
                    if (!out.empty()) out.push_back(' ');
                    out.append(fmt(a));
                }
                return out;
            },
            [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
                std::istringstream in(v);
                std::vector<float> at;
                for (std::string w; in >> w;) {
                    char* end = nullptr;
                    const float x = std::strtof(w.c_str(), &end);
                    if (!end || *end != '\0' || !std::isfinite(x))
                        return input_error("cut slices: numbers, e.g. \"1 2.5 4\"");
                    at.push_back(x);
                }
                s.cut_plane.slices = std::move(at);
                return ok_status();
            }};
}

// The grey-level volume on the caps, a path relative to the manifest: empty text unsets it.
Field cut_volume_field() {
    return {"cut_plane.volume",
            "cut slices volume",
            FieldScope::Scene,
            FieldKind::Text,
            [](const Scene& s, const FieldTarget&) { return s.cut_plane.volume; },
            [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
                const size_t a = v.find_first_not_of(" \t"), b = v.find_last_not_of(" \t");
                s.cut_plane.volume = a == std::string::npos ? std::string() : v.substr(a, b - a + 1);
                const std::filesystem::path file(s.cut_plane.volume);
                s.cut_plane.volume_path = s.cut_plane.volume.empty() || file.is_absolute() || s.base_dir.empty()
                                              ? s.cut_plane.volume
                                              : (std::filesystem::path(s.base_dir) / file).string();
                return ok_status();
            }};
}

// The volume's image around the caps as well: true or false.
Field cut_volume_around_field() {
    return {
        "cut_plane.volume_around",
        "cut volume around caps",
        FieldScope::Scene,
        FieldKind::Choice,
        [](const Scene& s, const FieldTarget&) { return std::string(s.cut_plane.volume_around ? "true" : "false"); },
        [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
            if (v != "true" && v != "false") return input_error("cut volume around caps: true or false");
            s.cut_plane.volume_around = v == "true";
            return ok_status();
        },
        bool_choices};
}

// The cut plane's preset normals (scene.h CutPlaneSettings): empty text unsets one.
template <size_t I>
Field cut_axis_field(const char* key, const char* label) {
    return {key,
            label,
            FieldScope::Scene,
            FieldKind::Vec3,
            [](const Scene& s, const FieldTarget&) {
                const auto& n = s.cut_plane.axes[I];
                return n ? fmt3(*n) : std::string();
            },
            [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
                if (v.find_first_not_of(" \t") == std::string::npos) {
                    s.cut_plane.axes[I].reset();
                    return ok_status();
                }
                std::array<float, 3> n{};
                if (auto r = parse_vec3(v, "cut plane normal", n); !r) return r;
                s.cut_plane.axes[I] = n;
                return ok_status();
            }};
}

std::vector<Field> cut_plane_fields() {
    return {cut_axis_field<0>("cut_plane.axial", "cut axial normal"),
            cut_axis_field<1>("cut_plane.coronal", "cut coronal normal"),
            cut_axis_field<2>("cut_plane.sagittal", "cut sagittal normal"),
            cut_slice_normal_field(),
            cut_slices_field(),
            cut_volume_field(),
            cut_volume_around_field()};
}

std::vector<Field> all_fields() {
    std::vector<Field> out;
    // `version` and `models` have no value to type: the version is always 1, and
    // the models array is edited by the add and remove commands (panel buttons).
    out.push_back({"version", "version", FieldScope::Scene, FieldKind::Fixed,
                   [](const Scene&, const FieldTarget&) { return std::string("1"); },
                   [](Scene&, const FieldTarget&, const std::string& v) -> Status {
                       return v == "1" ? ok_status() : input_error("version: only 1 exists");
                   }});
    out.push_back({"models", "models", FieldScope::Scene, FieldKind::Fixed,
                   [](const Scene& s, const FieldTarget&) { return std::to_string(s.models.size()); },
                   [](Scene&, const FieldTarget&, const std::string&) -> Status {
                       return input_error("models: use Add model / Remove model");
                   }});
    for (auto* part : {&model_fields, &pin_fields, &group_fields, &camera_fields, &kiosk_fields, &kiosk_tour_fields,
                       &kiosk_access_fields, &cut_plane_fields, &tour_fields})
        for (Field& f : part()) out.push_back(f);
    return out;
}

}  // namespace

const std::vector<Field>& scene_fields() {
    static const std::vector<Field> fields = all_fields();
    return fields;
}

std::string next_choice(const std::vector<std::string>& choices, const std::string& current) {
    if (choices.empty()) return current;
    const auto it = std::find(choices.begin(), choices.end(), current);
    if (it == choices.end() || it + 1 == choices.end()) return choices.front();
    return *(it + 1);
}

}  // namespace body::kiosk::author
