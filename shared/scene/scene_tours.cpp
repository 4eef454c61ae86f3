// scene.json's tours, pinned labels and the kiosk's tour settings (contract in
// scene_tours.h, schema in SCENE.md). Unknown keys are errors, as elsewhere.
#include "shared/scene/scene_tours.h"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <set>

namespace body::scene::detail {

namespace {

using nlohmann::json;

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

bool fail(Failure& f, const std::string& where, const std::string& why) {
    f = Failure{where, why};
    return false;
}

bool only_keys(const json& v, const std::string& path, std::initializer_list<const char*> keys, Failure& f) {
    if (!v.is_object()) return fail(f, path, "expected an object");
    for (const auto& [key, value] : v.items()) {
        bool known = false;
        for (const char* k : keys) known = known || key == k;
        if (!known) return fail(f, path + "." + key, "unknown key");
    }
    return true;
}

bool number(const json& v, const std::string& path, float lo, float hi, float& out, Failure& f) {
    if (!v.is_number()) return fail(f, path, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d) || d < lo || d > hi) {
        return fail(f, path, "expected a number in [" + fmt(lo) + ", " + fmt(hi) + "]");
    }
    out = static_cast<float>(d);
    return true;
}

bool string(const json& v, const std::string& path, std::string& out, Failure& f) {
    if (!v.is_string()) return fail(f, path, "expected a string");
    out = v.get<std::string>();
    if (out.empty()) return fail(f, path, "must not be empty");
    return true;
}

bool vec3(const json& v, const std::string& path, std::array<float, 3>& out, Failure& f) {
    if (!v.is_array() || v.size() != 3) return fail(f, path, "expected an array of 3 numbers");
    for (size_t i = 0; i < 3; ++i) {
        if (!number(v[i], path + "[" + std::to_string(i) + "]", -1e6f, 1e6f, out[i], f)) return false;
    }
    return true;
}

// language -> "title" or {"title", "description"}, as models[].label.
bool texts(const json& v, const std::string& path, std::vector<LabelText>& out, Failure& f) {
    if (!v.is_object() || v.empty()) {
        return fail(f, path, "expected an object of languages, e.g. {\"en\": \"text\"}");
    }
    for (const auto& [language, entry] : v.items()) {
        const std::string p = path + "." + language;
        LabelText t;
        t.language = language;
        if (entry.is_string()) {
            if (!string(entry, p, t.title, f)) return false;
        } else {
            if (!only_keys(entry, p, {"title", "description"}, f)) return false;
            if (!entry.contains("title")) return fail(f, p + ".title", "missing");
            if (!string(entry["title"], p + ".title", t.title, f)) return false;
            if (entry.contains("description")) {
                if (!entry["description"].is_string()) return fail(f, p + ".description", "expected a string");
                t.description = entry["description"].get<std::string>();
            }
        }
        out.push_back(std::move(t));
    }
    return true;
}

bool names(const json& v, const std::string& path, std::vector<std::string>& out, Failure& f) {
    if (!v.is_array()) return fail(f, path, "expected an array of model or group names");
    for (size_t i = 0; i < v.size(); ++i) {
        std::string n;
        if (!string(v[i], path + "[" + std::to_string(i) + "]", n, f)) return false;
        out.push_back(std::move(n));
    }
    return true;
}

bool easing(const json& v, const std::string& path, Easing& out, Failure& f) {
    std::string s;
    if (!string(v, path, s, f)) return false;
    if (s == "linear") {
        out = Easing::Linear;
    } else if (s == "ease-in") {
        out = Easing::EaseIn;
    } else if (s == "ease-out") {
        out = Easing::EaseOut;
    } else if (s == "ease-in-out") {
        out = Easing::EaseInOut;
    } else {
        return fail(f, path, "expected linear, ease-in, ease-out or ease-in-out");
    }
    return true;
}

bool camera(const json& v, const std::string& path, TourCamera& c, Failure& f) {
    if (!only_keys(v, path, {"target", "azimuth_deg", "polar_deg", "distance"}, f)) return false;
    float x = 0.0f;
    if (v.contains("target")) {
        std::array<float, 3> t{};
        if (!vec3(v["target"], path + ".target", t, f)) return false;
        c.target = t;
    }
    if (v.contains("azimuth_deg")) {
        if (!number(v["azimuth_deg"], path + ".azimuth_deg", -360, 360, x, f)) return false;
        c.azimuth_deg = x;
    }
    if (v.contains("polar_deg")) {
        if (!number(v["polar_deg"], path + ".polar_deg", 1, 179, x, f)) return false;
        c.polar_deg = x;
    }
    if (v.contains("distance")) {
        if (!number(v["distance"], path + ".distance", 0, 1e7f, x, f)) return false;
        c.distance = x;
    }
    return true;
}

// steps[].cut: {"axis": name, "offset": d} or {"normal": [x, y, z], "offset": d}.
bool tour_cut(const json& v, const std::string& path, TourCut& c, Failure& f) {
    if (!only_keys(v, path, {"axis", "normal", "offset"}, f)) return false;
    if (v.contains("axis") == v.contains("normal")) return fail(f, path, "expected one of axis and normal");
    if (v.contains("axis")) {
        std::string a;
        if (!string(v["axis"], path + ".axis", a, f)) return false;
        c.axis = a == "axial" ? 0 : a == "coronal" ? 1 : a == "sagittal" ? 2 : -1;
        if (c.axis < 0) return fail(f, path + ".axis", "expected axial, coronal or sagittal");
    } else {
        if (!vec3(v["normal"], path + ".normal", c.normal, f)) return false;
        if (c.normal[0] == 0.0f && c.normal[1] == 0.0f && c.normal[2] == 0.0f)
            return fail(f, path + ".normal", "expected a non-zero normal");
    }
    return !v.contains("offset") || number(v["offset"], path + ".offset", -1e7f, 1e7f, c.offset, f);
}

bool step(const json& v, const std::string& path, TourStep& s, Failure& f) {
    if (!only_keys(v, path, {"camera", "visible", "styles", "select", "caption", "duration", "hold", "easing", "cut"},
                   f)) {
        return false;
    }
    if (v.contains("cut") && !tour_cut(v["cut"], path + ".cut", s.cut.emplace(), f)) return false;
    if (v.contains("camera") && !camera(v["camera"], path + ".camera", s.camera, f)) return false;
    if (v.contains("visible")) {
        s.visible.emplace();
        if (!names(v["visible"], path + ".visible", *s.visible, f)) return false;
    }
    if (v.contains("styles")) {
        const json& st = v["styles"];
        if (!st.is_object()) return fail(f, path + ".styles", "expected an object of name -> style");
        for (const auto& [name, value] : st.items()) {
            const std::string p = path + ".styles." + name;
            std::string style;
            if (!string(value, p, style, f)) return false;
            const auto parsed = parse_style(style);
            if (!parsed) return fail(f, p, "unknown style '" + style + "'");
            s.styles.emplace_back(name, *parsed);
        }
    }
    if (v.contains("select") && !string(v["select"], path + ".select", s.select, f)) return false;
    if (v.contains("caption") && !texts(v["caption"], path + ".caption", s.caption, f)) return false;
    if (v.contains("duration") && !number(v["duration"], path + ".duration", 0, 600, s.duration, f)) return false;
    if (v.contains("hold") && !number(v["hold"], path + ".hold", 0, 3600, s.hold, f)) return false;
    if (v.contains("easing") && !easing(v["easing"], path + ".easing", s.easing, f)) return false;
    return true;
}

// Every language in `t` listed; unnamed ones become the default.
bool check_languages(std::vector<LabelText>& t, const std::set<std::string>& languages, const std::string& first,
                     const std::string& path, Failure& f) {
    for (LabelText& x : t) {
        if (x.language.empty()) x.language = first;
        if (!languages.count(x.language))
            return fail(f, path + "." + x.language, "language not listed in kiosk.languages");
    }
    return true;
}

}  // namespace

bool read_pins(const json& v, const std::string& path, std::vector<Pin>& out, Failure& f) {
    if (!v.is_array()) return fail(f, path, "expected an array of pins");
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string p = path + "[" + std::to_string(i) + "]";
        Pin pin;
        if (!only_keys(v[i], p, {"anchor", "label"}, f)) return false;
        if (!v[i].contains("anchor")) return fail(f, p + ".anchor", "missing");
        if (!vec3(v[i]["anchor"], p + ".anchor", pin.anchor, f)) return false;
        if (!v[i].contains("label")) return fail(f, p + ".label", "missing");
        if (!texts(v[i]["label"], p + ".label", pin.labels, f)) return false;
        out.push_back(std::move(pin));
    }
    return true;
}

bool read_kiosk_tour_settings(const json& k, const std::string& path, KioskSettings& out, Failure& f) {
    if (k.contains("attract_tour") && !string(k["attract_tour"], path + ".attract_tour", out.attract_tour, f)) {
        return false;
    }
    if (k.contains("countdown_seconds") &&
        !number(k["countdown_seconds"], path + ".countdown_seconds", 0, 600, out.countdown_seconds, f)) {
        return false;
    }
    if (k.contains("operator_pin")) {
        const json& p = k["operator_pin"];
        const std::string where = path + ".operator_pin";
        if (!p.is_string()) return fail(f, where, "expected a string of 4 to 12 digits");
        out.operator_pin = p.get<std::string>();
        const bool digits = out.operator_pin.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || out.operator_pin.size() < 4 || out.operator_pin.size() > 12) {
            return fail(f, where, "expected a string of 4 to 12 digits");
        }
    }
    if (k.contains("pins")) {
        if (!k["pins"].is_boolean()) return fail(f, path + ".pins", "expected true or false");
        out.pins = k["pins"].get<bool>();
    }
    return true;
}

bool read_tours(const json& v, const std::string& path, std::vector<Tour>& out, Failure& f) {
    if (!v.is_array()) return fail(f, path, "expected an array of tours");
    for (size_t i = 0; i < v.size(); ++i) {
        const std::string p = path + "[" + std::to_string(i) + "]";
        Tour tour;
        if (!only_keys(v[i], p, {"name", "title", "steps"}, f)) return false;
        if (!v[i].contains("name")) return fail(f, p + ".name", "missing");
        if (!string(v[i]["name"], p + ".name", tour.name, f)) return false;
        if (v[i].contains("title") && !texts(v[i]["title"], p + ".title", tour.title, f)) return false;
        if (!v[i].contains("steps")) return fail(f, p + ".steps", "missing");
        const json& steps = v[i]["steps"];
        if (!steps.is_array() || steps.empty()) return fail(f, p + ".steps", "expected a non-empty array");
        for (size_t j = 0; j < steps.size(); ++j) {
            TourStep s;
            if (!step(steps[j], p + ".steps[" + std::to_string(j) + "]", s, f)) return false;
            tour.steps.push_back(std::move(s));
        }
        out.push_back(std::move(tour));
    }
    return true;
}

bool check_tour_references(Scene& s, Failure& f) {
    const std::set<std::string> languages(s.kiosk.languages.begin(), s.kiosk.languages.end());
    const std::string& first = s.kiosk.languages.front();
    for (size_t i = 0; i < s.models.size(); ++i) {
        for (size_t j = 0; j < s.models[i].pins.size(); ++j) {
            const std::string p = "models[" + std::to_string(i) + "].pins[" + std::to_string(j) + "].label";
            if (!check_languages(s.models[i].pins[j].labels, languages, first, p, f)) return false;
        }
    }
    const auto known = [&](const std::string& n) { return s.model_index(n) >= 0 || s.find_group(n) != nullptr; };
    std::set<std::string> tour_names;
    for (size_t i = 0; i < s.tours.size(); ++i) {
        Tour& t = s.tours[i];
        const std::string p = "tours[" + std::to_string(i) + "]";
        if (!tour_names.insert(t.name).second) return fail(f, p + ".name", "duplicate tour '" + t.name + "'");
        if (!check_languages(t.title, languages, first, p + ".title", f)) return false;
        for (size_t j = 0; j < t.steps.size(); ++j) {
            TourStep& st = t.steps[j];
            const std::string q = p + ".steps[" + std::to_string(j) + "]";
            if (!check_languages(st.caption, languages, first, q + ".caption", f)) return false;
            for (size_t k = 0; st.visible && k < st.visible->size(); ++k) {
                if (!known((*st.visible)[k])) {
                    return fail(f, q + ".visible[" + std::to_string(k) + "]",
                                "no model or group named '" + (*st.visible)[k] + "'");
                }
            }
            for (const auto& [name, style] : st.styles) {
                if (!known(name)) return fail(f, q + ".styles." + name, "no model or group of that name");
            }
            if (!st.select.empty() && s.model_index(st.select) < 0) {
                return fail(f, q + ".select", "no model named '" + st.select + "'");
            }
        }
    }
    if (!s.kiosk.attract_tour.empty() && s.tour_index(s.kiosk.attract_tour) < 0) {
        return fail(f, "kiosk.attract_tour", "no tour named '" + s.kiosk.attract_tour + "' in tours");
    }
    return true;
}

}  // namespace body::scene::detail
