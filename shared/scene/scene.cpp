// scene.json parsing and validation (schema: shared/scene/SCENE.md).
// Unknown keys are errors so that a typo never silently changes a kiosk.
#include "shared/scene/scene.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>
#include <type_traits>

#include "shared/atomic_file.h"
#include "shared/input_file.h"
#include "shared/scene/scene_access.h"
#include "shared/scene/scene_tours.h"

namespace body::scene {

namespace {

using nlohmann::json;

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

// A place in the file for a message ("models[3].colour[1]"): a string, or a
// function that makes one, so that the thousands of places a large scene's
// models have are built only for the one that fails.
template <class P>
std::string place(const P& p) {
    if constexpr (std::is_invocable_v<const P&>)
        return p();
    else
        return std::string(p);
}

// The place of `key` inside the place `p` (p must outlive it).
template <class P>
auto child(const P& p, const char* key) {
    return [&p, key] { return place(p) + "." + key; };
}

// The member `key` of `object`, or null.
const json* member(const json& object, const char* key) {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

// Carries the file name and the first error; each reader returns false after failing.
struct Reader {
    std::string source;
    std::string message;

    // The message is one line: control characters from the file (in names, keys, values) are escaped.
    bool fail(const std::string& path, const std::string& reason) {
        if (message.empty()) message = source + ": " + escape_control_characters(path + ": " + reason);
        return false;
    }

    template <class P>
    bool only_keys(const json& object, const P& path, std::initializer_list<const char*> keys) {
        if (!object.is_object()) return fail(place(path), "expected an object");
        for (auto it = object.begin(); it != object.end(); ++it) {
            const std::string& key = it.key();
            bool known = false;
            for (const char* k : keys) known = known || key == k;
            if (!known) return fail(place(path) + "." + key, "unknown key");
        }
        return true;
    }

    template <class P>
    bool number(const json& v, const P& path, float lo, float hi, float& out) {
        if (!v.is_number()) return fail(place(path), "expected a number");
        double d = v.get<double>();
        if (!std::isfinite(d) || d < lo || d > hi) {
            return fail(place(path), "expected a number in [" + fmt(lo) + ", " + fmt(hi) + "]");
        }
        out = static_cast<float>(d);
        return true;
    }

    template <class P>
    bool integer(const json& v, const P& path, int lo, int hi, int& out) {
        if (!v.is_number_integer() || v.get<long>() < lo || v.get<long>() > hi) {
            return fail(place(path), "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
        }
        out = static_cast<int>(v.get<long>());
        return true;
    }

    template <class P>
    bool string(const json& v, const P& path, std::string& out, bool allow_empty = false) {
        if (!v.is_string()) return fail(place(path), "expected a string");
        out = v.get_ref<const std::string&>();
        if (!allow_empty && out.empty()) return fail(place(path), "must not be empty");
        return true;
    }

    template <class P>
    bool boolean(const json& v, const P& path, bool& out) {
        if (!v.is_boolean()) return fail(place(path), "expected true or false");
        out = v.get<bool>();
        return true;
    }

    template <class P>
    bool vec3(const json& v, const P& path, float lo, float hi, std::array<float, 3>& out) {
        if (!v.is_array() || v.size() != 3) return fail(place(path), "expected an array of 3 numbers");
        for (size_t i = 0; i < 3; ++i) {
            const auto at = [&] { return place(path) + "[" + std::to_string(i) + "]"; };
            if (!number(v[i], at, lo, hi, out[i])) return false;
        }
        return true;
    }

    template <class P>
    bool style(const json& v, const P& path, Style& out) {
        std::string name;
        if (!string(v, path, name)) return false;
        auto s = parse_style(name);
        if (!s)
            return fail(place(path),
                        "unknown style '" + name + "' (wireframe, smooth, lines, hatching, hatching-2tone)");
        out = *s;
        return true;
    }

    template <class P>
    bool lod(const json& v, const P& path, Lod& out) {
        if (v.is_string() && v.get_ref<const std::string&>() == "auto") {
            out = Lod{};
            return true;
        }
        if (!v.is_number()) return fail(place(path), "expected \"auto\" or a ratio in (0, 1]");
        double d = v.get<double>();
        if (!std::isfinite(d) || d <= 0.0 || d > 1.0)
            return fail(place(path), "expected \"auto\" or a ratio in (0, 1]");
        out = Lod{false, static_cast<float>(d)};
        return true;
    }

    template <class P>
    bool transform(const json& v, const P& path, Transform& out) {
        if (!only_keys(v, path, {"translate", "rotate_deg", "scale"})) return false;
        if (const json* t = member(v, "translate");
            t && !vec3(*t, child(path, "translate"), -1e6f, 1e6f, out.translate))
            return false;
        if (const json* r = member(v, "rotate_deg");
            r && !vec3(*r, child(path, "rotate_deg"), -360, 360, out.rotate_deg))
            return false;
        if (const json* s = member(v, "scale"); s && !number(*s, child(path, "scale"), 1e-6f, 1e6f, out.scale))
            return false;
        return true;
    }

    template <class P>
    bool labels(const json& v, const P& path, std::vector<LabelText>& out) {
        if (!v.is_object() || v.empty()) {
            return fail(place(path), "expected an object of languages, e.g. {\"en\": {\"title\": ...}}");
        }
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string& language = it.key();
            const json& entry = it.value();
            const auto p = [&] { return place(path) + "." + language; };
            LabelText text;
            text.language = language;
            if (entry.is_string()) {
                text.title = entry.get_ref<const std::string&>();
            } else {
                if (!only_keys(entry, p, {"title", "description"})) return false;
                const json* title = member(entry, "title");
                if (!title) return fail(p() + ".title", "missing");
                if (!string(*title, child(p, "title"), text.title)) return false;
                if (const json* d = member(entry, "description");
                    d && !string(*d, child(p, "description"), text.description, true))
                    return false;
            }
            out.push_back(std::move(text));
        }
        return true;
    }
};

// `file` as seen from `base_dir` (std::filesystem's base_dir / file on POSIX, without building paths).
std::string beside(const std::string& base_dir, const std::string& file) {
    if (file.front() == '/' || base_dir.empty()) return file;
    return base_dir.back() == '/' ? base_dir + file : base_dir + "/" + file;
}

bool read_model(Reader& r, const json& v, size_t index, const std::string& base_dir, Model& m) {
    const auto path = [index] { return "models[" + std::to_string(index) + "]"; };
    if (!r.only_keys(v, path, {"name", "file", "group", "colour", "transform", "style", "lod", "label", "pins"})) {
        return false;
    }
    const json* name = member(v, "name");
    if (!name) return r.fail(path() + ".name", "missing");
    if (!r.string(*name, child(path, "name"), m.name)) return false;
    const json* file = member(v, "file");
    if (!file) return r.fail(path() + ".file", "missing");
    if (!r.string(*file, child(path, "file"), m.file)) return false;
    m.path = beside(base_dir, m.file);
    if (const json* g = member(v, "group"); g && !r.string(*g, child(path, "group"), m.group)) return false;
    if (const json* c = member(v, "colour"); c && !r.vec3(*c, child(path, "colour"), 0, 1, m.colour)) return false;
    if (const json* t = member(v, "transform"); t && !r.transform(*t, child(path, "transform"), m.transform))
        return false;
    if (const json* s = member(v, "style"); s && !r.style(*s, child(path, "style"), m.style)) return false;
    if (const json* l = member(v, "lod"); l && !r.lod(*l, child(path, "lod"), m.lod)) return false;
    if (const json* l = member(v, "label")) {
        if (!r.labels(*l, child(path, "label"), m.labels)) return false;
    } else {
        m.labels.push_back(LabelText{"", m.name, ""});
    }
    detail::Failure f;
    if (const json* p = member(v, "pins"); p && !detail::read_pins(*p, path() + ".pins", m.pins, f))
        return r.fail(f.where, f.why);
    return true;
}

bool read_group(Reader& r, const json& v, const std::string& path, Group& g) {
    if (!r.only_keys(v, path, {"name", "style", "lod", "visible"})) return false;
    if (!v.contains("name")) return r.fail(path + ".name", "missing");
    if (!r.string(v["name"], path + ".name", g.name)) return false;
    if (v.contains("style")) {
        Style s{};
        if (!r.style(v["style"], path + ".style", s)) return false;
        g.style = s;
    }
    if (v.contains("lod")) {
        Lod l;
        if (!r.lod(v["lod"], path + ".lod", l)) return false;
        g.lod = l;
    }
    if (v.contains("visible") && !r.boolean(v["visible"], path + ".visible", g.visible)) return false;
    return true;
}

bool read_camera(Reader& r, const json& v, const std::string& path, HomeCamera& c) {
    if (!r.only_keys(v, path, {"target", "azimuth_deg", "polar_deg", "distance", "fov_deg"})) return false;
    if (v.contains("target") && !r.vec3(v["target"], path + ".target", -1e6f, 1e6f, c.target)) return false;
    if (v.contains("azimuth_deg") && !r.number(v["azimuth_deg"], path + ".azimuth_deg", -360, 360, c.azimuth_deg)) {
        return false;
    }
    if (v.contains("polar_deg") && !r.number(v["polar_deg"], path + ".polar_deg", 1, 179, c.polar_deg)) return false;
    if (v.contains("distance") && !r.number(v["distance"], path + ".distance", 0, 1e7f, c.distance)) return false;
    if (v.contains("fov_deg") && !r.number(v["fov_deg"], path + ".fov_deg", 5, 120, c.fov_deg)) return false;
    return true;
}

bool read_kiosk(Reader& r, const json& v, const std::string& path, KioskSettings& k) {
    if (!r.only_keys(
            v, path,
            {"idle_seconds", "reset_seconds", "languages", "admin_gesture", "frame_ms_target", "attract_tour",
             "countdown_seconds", "pins", "operator_pin", "high_contrast", "large_text", "access_buttons", "icons"})) {
        return false;
    }
    if (detail::Failure f; !detail::read_kiosk_tour_settings(v, path, k, f)) return r.fail(f.where, f.why);
    if (detail::Failure f; !detail::read_kiosk_access_settings(v, path, k, f)) return r.fail(f.where, f.why);
    if (v.contains("idle_seconds") && !r.number(v["idle_seconds"], path + ".idle_seconds", 1, 86400, k.idle_seconds)) {
        return false;
    }
    if (v.contains("reset_seconds") &&
        !r.number(v["reset_seconds"], path + ".reset_seconds", 1, 86400, k.reset_seconds)) {
        return false;
    }
    if (k.reset_seconds < k.idle_seconds) {
        return r.fail(path + ".reset_seconds", "must not be shorter than idle_seconds");
    }
    if (v.contains("frame_ms_target") &&
        !r.number(v["frame_ms_target"], path + ".frame_ms_target", 1, 1000, k.frame_ms_target)) {
        return false;
    }
    if (v.contains("languages")) {
        const json& langs = v["languages"];
        if (!langs.is_array() || langs.empty()) return r.fail(path + ".languages", "expected a non-empty array");
        k.languages.clear();
        std::set<std::string> seen;
        for (size_t i = 0; i < langs.size(); ++i) {
            std::string lang;
            const std::string p = path + ".languages[" + std::to_string(i) + "]";
            if (!r.string(langs[i], p, lang)) return false;
            if (!seen.insert(lang).second) return r.fail(p, "duplicate language '" + lang + "'");
            k.languages.push_back(lang);
        }
    }
    if (v.contains("admin_gesture")) {
        const json& a = v["admin_gesture"];
        const std::string p = path + ".admin_gesture";
        if (!r.only_keys(a, p, {"corner", "taps", "seconds", "corner_size"})) return false;
        if (a.contains("corner")) {
            std::string corner;
            if (!r.string(a["corner"], p + ".corner", corner)) return false;
            if (corner == "top-left") {
                k.admin.corner = AdminGesture::Corner::TopLeft;
            } else if (corner == "top-right") {
                k.admin.corner = AdminGesture::Corner::TopRight;
            } else if (corner == "bottom-left") {
                k.admin.corner = AdminGesture::Corner::BottomLeft;
            } else if (corner == "bottom-right") {
                k.admin.corner = AdminGesture::Corner::BottomRight;
            } else {
                return r.fail(p + ".corner", "expected top-left, top-right, bottom-left or bottom-right");
            }
        }
        if (a.contains("taps") && !r.integer(a["taps"], p + ".taps", 3, 20, k.admin.taps)) return false;
        if (a.contains("seconds") && !r.number(a["seconds"], p + ".seconds", 0.5f, 30, k.admin.seconds)) return false;
        if (a.contains("corner_size") &&
            !r.number(a["corner_size"], p + ".corner_size", 0.02f, 0.5f, k.admin.corner_size)) {
            return false;
        }
    }
    return true;
}

bool read_cut_plane(Reader& r, const json& v, const std::string& path, const std::string& base_dir,
                    CutPlaneSettings& c) {
    const char* names[] = {"axial", "coronal", "sagittal"};
    if (!r.only_keys(v, path, {names[0], names[1], names[2], "slices", "slice_normal", "volume", "volume_around"}))
        return false;
    if (v.contains("volume_around") && !r.boolean(v["volume_around"], path + ".volume_around", c.volume_around))
        return false;
    if (v.contains("volume")) {
        if (!r.string(v["volume"], path + ".volume", c.volume)) return false;
        const std::filesystem::path file(c.volume);
        c.volume_path =
            file.is_absolute() || base_dir.empty() ? file.string() : (std::filesystem::path(base_dir) / file).string();
    }
    if (v.contains("slice_normal")) {
        std::array<float, 3> n{};
        if (!r.vec3(v["slice_normal"], path + ".slice_normal", -1e6f, 1e6f, n)) return false;
        if (std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) < 1e-6f)
            return r.fail(path + ".slice_normal", "expected a non-zero direction");
        c.slice_normal = n;
    }
    if (v.contains("slices")) {
        const json& a = v["slices"];
        if (!a.is_array() || a.size() > 100000) return r.fail(path + ".slices", "expected an array of numbers");
        for (size_t i = 0; i < a.size(); ++i) {
            float x = 0.0f;
            if (!r.number(a[i], path + ".slices[" + std::to_string(i) + "]", -1e7f, 1e7f, x)) return false;
            c.slices.push_back(x);
        }
    }
    for (size_t i = 0; i < 3; ++i) {
        if (!v.contains(names[i])) continue;
        std::array<float, 3> n{};
        const std::string p = path + "." + names[i];
        if (!r.vec3(v[names[i]], p, -1e6f, 1e6f, n)) return false;
        if (std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) < 1e-6f)
            return r.fail(p, "expected a non-zero direction");
        c.axes[i] = n;
    }
    return true;
}

// Cross-references: unique names, groups that exist, label languages that are declared.
bool check_references(Reader& r, Scene& s) {
    std::set<std::string> groups;
    for (size_t i = 0; i < s.groups.size(); ++i) {
        if (!groups.insert(s.groups[i].name).second) {
            return r.fail("groups[" + std::to_string(i) + "].name", "duplicate group '" + s.groups[i].name + "'");
        }
    }
    std::set<std::string> names;
    const std::set<std::string> languages(s.kiosk.languages.begin(), s.kiosk.languages.end());
    for (size_t i = 0; i < s.models.size(); ++i) {
        Model& m = s.models[i];
        const auto p = [i] { return "models[" + std::to_string(i) + "]"; };
        if (!names.insert(m.name).second) return r.fail(p() + ".name", "duplicate model '" + m.name + "'");
        if (!m.group.empty() && !groups.count(m.group)) {
            return r.fail(p() + ".group", "no group named '" + m.group + "' in groups");
        }
        for (LabelText& t : m.labels) {
            if (t.language.empty()) t.language = s.kiosk.languages.front();
            if (!languages.count(t.language)) {
                return r.fail(p() + ".label." + t.language, "language not listed in kiosk.languages");
            }
        }
    }
    return true;
}

}  // namespace

const Group* Scene::find_group(const std::string& name) const {
    for (const Group& g : groups) {
        if (g.name == name) return &g;
    }
    return nullptr;
}

int Scene::model_index(const std::string& name) const {
    for (size_t i = 0; i < models.size(); ++i) {
        if (models[i].name == name) return static_cast<int>(i);
    }
    return -1;
}

const LabelText& Scene::label(const Model& model, const std::string& language) const {
    assert(!model.labels.empty());
    for (const LabelText& t : model.labels) {
        if (t.language == language) return t;
    }
    for (const LabelText& t : model.labels) {
        if (t.language == kiosk.languages.front()) return t;
    }
    return model.labels.front();
}

const LabelText* Scene::text(const std::vector<LabelText>& texts, const std::string& language) const {
    for (const LabelText& t : texts) {
        if (t.language == language) return &t;
    }
    for (const LabelText& t : texts) {
        if (t.language == kiosk.languages.front()) return &t;
    }
    return texts.empty() ? nullptr : &texts.front();
}

int Scene::tour_index(const std::string& name) const {
    for (size_t i = 0; i < tours.size(); ++i) {
        if (tours[i].name == name) return static_cast<int>(i);
    }
    return -1;
}

Result<Scene> parse_scene(const std::string& text, const std::string& source, const std::string& base_dir) {
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        return input_error(source + ": byte " + std::to_string(e.byte) + ": not valid JSON");
    } catch (const json::exception& e) {  // 406: a number too large for a double (found by fuzzing)
        return input_error(source + ": not valid JSON: " + escape_for_message(e.what(), 120));
    }
    Reader r{source, {}};
    Scene s;
    s.source = source;
    s.base_dir = base_dir;
    if (!r.only_keys(root, "$", {"version", "models", "groups", "camera", "kiosk", "tours", "cut_plane"})) {
        return input_error(r.message);
    }
    if (root.contains("version")) {
        int version = 0;
        if (!r.integer(root["version"], "version", 1, 1, version)) return input_error(r.message);
    }
    if (root.contains("kiosk") && !read_kiosk(r, root["kiosk"], "kiosk", s.kiosk)) return input_error(r.message);
    if (root.contains("cut_plane") && !read_cut_plane(r, root["cut_plane"], "cut_plane", base_dir, s.cut_plane))
        return input_error(r.message);
    if (root.contains("groups")) {
        const json& groups = root["groups"];
        if (!groups.is_array()) return input_error(source + ": groups: expected an array");
        for (size_t i = 0; i < groups.size(); ++i) {
            Group g;
            if (!read_group(r, groups[i], "groups[" + std::to_string(i) + "]", g)) return input_error(r.message);
            s.groups.push_back(std::move(g));
        }
    }
    if (!root.contains("models")) return input_error(source + ": models: missing");
    const json& models = root["models"];
    if (!models.is_array() || models.empty()) return input_error(source + ": models: expected a non-empty array");
    s.models.reserve(models.size());
    for (size_t i = 0; i < models.size(); ++i) {
        Model m;
        if (!read_model(r, models[i], i, base_dir, m)) return input_error(r.message);
        s.models.push_back(std::move(m));
    }
    if (root.contains("camera") && !read_camera(r, root["camera"], "camera", s.camera)) return input_error(r.message);
    if (!check_references(r, s)) return input_error(r.message);
    detail::Failure f;
    if (root.contains("tours") && !detail::read_tours(root["tours"], "tours", s.tours, f)) {
        r.fail(f.where, f.why);
        return input_error(r.message);
    }
    if (!detail::check_tour_references(s, f)) {
        r.fail(f.where, f.why);
        return input_error(r.message);
    }
    return s;
}

Result<Scene> read_scene(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_scene(*text, path, std::filesystem::path(path).parent_path().string());
}

}  // namespace body::scene
