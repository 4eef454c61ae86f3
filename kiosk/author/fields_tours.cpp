// The editors of the tour and pin keys: models[].pins, kiosk.attract_tour,
// kiosk.countdown_seconds, kiosk.pins, kiosk.operator_pin, tours[] and their
// steps (contract in fields.h; helpers in fields_detail.h). Adding and removing
// pins, tours and steps are the editor's commands (editor.h).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <optional>
#include <sstream>

#include "kiosk/author/fields_detail.h"

namespace body::kiosk::author::detail {

namespace {

using scene::Scene;

scene::Pin& pin(Scene& s, const FieldTarget& t) {
    return s.models.at(static_cast<size_t>(t.model)).pins.at(static_cast<size_t>(t.pin));
}
const scene::Pin& pin(const Scene& s, const FieldTarget& t) {
    return s.models.at(static_cast<size_t>(t.model)).pins.at(static_cast<size_t>(t.pin));
}
scene::Tour& tour(Scene& s, const FieldTarget& t) { return s.tours.at(static_cast<size_t>(t.tour)); }
const scene::Tour& tour(const Scene& s, const FieldTarget& t) { return s.tours.at(static_cast<size_t>(t.tour)); }
scene::TourStep& step(Scene& s, const FieldTarget& t) { return tour(s, t).steps.at(static_cast<size_t>(t.step)); }
const scene::TourStep& step(const Scene& s, const FieldTarget& t) {
    return tour(s, t).steps.at(static_cast<size_t>(t.step));
}

const scene::LabelText* find_text(const std::vector<scene::LabelText>& texts, const std::string& language) {
    for (const scene::LabelText& l : texts)
        if (l.language == language) return &l;
    return nullptr;
}

// Sets the title in `language`; empty text removes that language's entry.
void set_text(std::vector<scene::LabelText>& texts, const std::string& language, const std::string& v) {
    auto it =
        std::find_if(texts.begin(), texts.end(), [&](const scene::LabelText& l) { return l.language == language; });
    if (v.empty()) {
        if (it != texts.end()) texts.erase(it);
    } else if (it != texts.end()) {
        it->title = v;
    } else {
        texts.push_back(scene::LabelText{language, v, ""});
    }
}

std::string title_of(const std::vector<scene::LabelText>& texts, const FieldTarget& t) {
    const scene::LabelText* l = find_text(texts, t.language);
    return l ? l->title : std::string();
}

// "a, b, c" <-> names (model and group names may hold spaces, not commas).
std::vector<std::string> split_list(const std::string& v) {
    std::vector<std::string> out;
    std::istringstream in(v);
    for (std::string part; std::getline(in, part, ',');) {
        const size_t b = part.find_first_not_of(" \t"), e = part.find_last_not_of(" \t");
        if (b != std::string::npos) out.push_back(part.substr(b, e - b + 1));
    }
    return out;
}
std::string join_list(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}

// An optional camera value: empty text unsets it (the step keeps the previous step's).
Status set_optional(std::optional<float>& out, const std::string& v, const char* what) {
    if (v.empty()) {
        out.reset();
        return ok_status();
    }
    float x = 0;
    if (auto s = parse_number(v, what, x); !s) return s;
    out = x;
    return ok_status();
}
std::string optional_text(const std::optional<float>& v) { return v ? fmt(*v) : std::string(); }

std::vector<std::string> tour_choices(const Scene& s) {
    std::vector<std::string> c{"none"};
    for (const scene::Tour& t : s.tours) c.push_back(t.name);
    return c;
}
std::vector<std::string> model_choices(const Scene& s) {
    std::vector<std::string> c{"none"};
    for (const scene::Model& m : s.models) c.push_back(m.name);
    return c;
}
// A step's cut as one line: "none", "<axis> <offset>" or "<nx> <ny> <nz> <offset>".
constexpr const char* kCutAxes[] = {"axial", "coronal", "sagittal"};
std::string cut_text(const std::optional<scene::TourCut>& c) {
    if (!c) return "none";
    if (c->axis >= 0 && c->axis < 3) return std::string(kCutAxes[c->axis]) + " " + fmt(c->offset);
    return fmt3(c->normal) + " " + fmt(c->offset);
}
Status parse_cut_text(const std::string& v, std::optional<scene::TourCut>& out) {
    const auto bad = [] {
        return input_error("step cut: none, \"axial 10\" (axis, offset) or \"0 1 0 10\" (normal, offset)");
    };
    std::istringstream in(v);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (words.size() == 1 && words[0] == "none") {
        out.reset();
        return ok_status();
    }
    scene::TourCut c;
    const auto number = [](const std::string& w, float& x) {
        char* end = nullptr;
        x = std::strtof(w.c_str(), &end);
        return end && *end == '\0' && end != w.c_str() && std::isfinite(x);
    };
    if (words.size() == 2) {
        const auto* it = std::find(std::begin(kCutAxes), std::end(kCutAxes), words[0]);
        if (it == std::end(kCutAxes) || !number(words[1], c.offset)) return bad();
        c.axis = static_cast<int>(it - std::begin(kCutAxes));
    } else if (words.size() == 4) {
        for (size_t i = 0; i < 3; ++i)
            if (!number(words[i], c.normal[i])) return bad();
        if (!number(words[3], c.offset) || (c.normal[0] == 0 && c.normal[1] == 0 && c.normal[2] == 0)) return bad();
    } else {
        return bad();
    }
    out = c;
    return ok_status();
}

std::vector<std::string> easing_choices(const Scene&) { return {"linear", "ease-in", "ease-out", "ease-in-out"}; }

std::vector<Field> step_fields() {
    return {
        {"steps[].camera", "step target", FieldScope::Step, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget& t) {
             const auto& v = step(s, t).camera.target;
             return v ? fmt3(*v) : std::string();
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             auto& out = step(s, t).camera.target;
             if (v.empty()) {
                 out.reset();
                 return ok_status();
             }
             std::array<float, 3> x{};
             if (auto r = parse_vec3(v, "step target", x); !r) return r;
             out = x;
             return ok_status();
         }},
        {"steps[].camera", "step azimuth", FieldScope::Step, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return optional_text(step(s, t).camera.azimuth_deg); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return set_optional(step(s, t).camera.azimuth_deg, v, "step azimuth");
         }},
        {"steps[].camera", "step polar", FieldScope::Step, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return optional_text(step(s, t).camera.polar_deg); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return set_optional(step(s, t).camera.polar_deg, v, "step polar");
         }},
        {"steps[].camera", "step distance", FieldScope::Step, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return optional_text(step(s, t).camera.distance); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return set_optional(step(s, t).camera.distance, v, "step distance");
         }},
        // "a, limbic": only these show; empty: the visibility before the tour.
        {"steps[].visible", "step visible", FieldScope::Step, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) {
             const auto& v = step(s, t).visible;
             return v ? join_list(*v) : std::string();
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             auto& out = step(s, t).visible;
             if (v.empty())
                 out.reset();
             else
                 out = split_list(v);
             return ok_status();
         }},
        // "a=hatching, limbic=smooth".
        {"steps[].styles", "step styles", FieldScope::Step, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) {
             std::vector<std::string> parts;
             for (const auto& [name, style] : step(s, t).styles) parts.push_back(name + "=" + style_name(style));
             return join_list(parts);
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             std::vector<std::pair<std::string, Style>> out;
             for (const std::string& part : split_list(v)) {
                 const size_t eq = part.find('=');
                 if (eq == std::string::npos) return input_error("step styles: name=style, e.g. \"a=hatching\"");
                 std::string name = part.substr(0, eq), style = part.substr(eq + 1);
                 while (!name.empty() && name.back() == ' ') name.pop_back();
                 style.erase(0, style.find_first_not_of(' '));
                 Style st{};
                 if (auto r = parse_style_text(style, "step styles", st); !r) return r;
                 out.emplace_back(name, st);
             }
             step(s, t).styles = std::move(out);
             return ok_status();
         }},
        {"steps[].select", "step select", FieldScope::Step, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) {
             const std::string& v = step(s, t).select;
             return v.empty() ? std::string("none") : v;
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             step(s, t).select = v == "none" ? std::string() : v;
             return ok_status();
         },
         model_choices},
        {"steps[].caption", "caption", FieldScope::StepCaption, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return title_of(step(s, t).caption, t); },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             set_text(step(s, t).caption, t.language, v);
             return ok_status();
         }},
        {"steps[].duration", "duration (s)", FieldScope::Step, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return fmt(step(s, t).duration); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_number(v, "duration", step(s, t).duration);
         }},
        {"steps[].hold", "hold (s)", FieldScope::Step, FieldKind::Number,
         [](const Scene& s, const FieldTarget& t) { return fmt(step(s, t).hold); },
         [](Scene& s, const FieldTarget& t, const std::string& v) { return parse_number(v, "hold", step(s, t).hold); }},
        {"steps[].easing", "easing", FieldScope::Step, FieldKind::Choice,
         [](const Scene& s, const FieldTarget& t) { return easing_choices(s)[static_cast<size_t>(step(s, t).easing)]; },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             const auto c = easing_choices(s);
             const auto it = std::find(c.begin(), c.end(), v);
             if (it == c.end()) return input_error("easing: linear, ease-in, ease-out or ease-in-out");
             step(s, t).easing = static_cast<scene::Easing>(it - c.begin());
             return ok_status();
         },
         easing_choices},
        {"steps[].cut", "step cut", FieldScope::Step, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return cut_text(step(s, t).cut); },
         [](Scene& s, const FieldTarget& t, const std::string& v) { return parse_cut_text(v, step(s, t).cut); }},
    };
}

}  // namespace

std::vector<Field> pin_fields() {
    return {
        {"models[].pins", "pin anchor", FieldScope::Pin, FieldKind::Vec3,
         [](const Scene& s, const FieldTarget& t) { return fmt3(pin(s, t).anchor); },
         [](Scene& s, const FieldTarget& t, const std::string& v) {
             return parse_vec3(v, "pin anchor", pin(s, t).anchor);
         }},
        {"models[].pins", "pin title", FieldScope::PinLabel, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return title_of(pin(s, t).labels, t); },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             set_text(pin(s, t).labels, t.language, v);
             return ok_status();
         }},
        {"models[].pins", "pin description", FieldScope::PinLabel, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) {
             const scene::LabelText* l = find_text(pin(s, t).labels, t.language);
             return l ? l->description : std::string();
         },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             auto& labels = pin(s, t).labels;
             if (!find_text(labels, t.language)) {  // a new language starts with the default language's title
                 const scene::LabelText* d = s.text(labels, t.language);
                 labels.push_back(scene::LabelText{t.language, d ? d->title : std::string(), ""});
             }
             for (scene::LabelText& l : labels)
                 if (l.language == t.language) l.description = v;
             return ok_status();
         }},
    };
}

std::vector<Field> kiosk_tour_fields() {
    return {
        {"kiosk.attract_tour", "attract tour", FieldScope::Scene, FieldKind::Choice,
         [](const Scene& s, const FieldTarget&) {
             return s.kiosk.attract_tour.empty() ? std::string("none") : s.kiosk.attract_tour;
         },
         [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
             s.kiosk.attract_tour = v == "none" ? std::string() : v;
             return ok_status();
         },
         tour_choices},
        {"kiosk.countdown_seconds", "countdown (s)", FieldScope::Scene, FieldKind::Number,
         [](const Scene& s, const FieldTarget&) { return fmt(s.kiosk.countdown_seconds); },
         [](Scene& s, const FieldTarget&, const std::string& v) {
             return parse_number(v, "countdown", s.kiosk.countdown_seconds);
         }},
        {"kiosk.pins", "pins", FieldScope::Scene, FieldKind::Choice,
         [](const Scene& s, const FieldTarget&) { return std::string(s.kiosk.pins ? "true" : "false"); },
         [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
             if (v != "true" && v != "false") return input_error("pins: true or false");
             s.kiosk.pins = v == "true";
             return ok_status();
         },
         bool_choices},
        // Empty: no operator mode (the admin gesture exits). The parser checks the 4-12 digits.
        {"kiosk.operator_pin", "operator PIN", FieldScope::Scene, FieldKind::Text,
         [](const Scene& s, const FieldTarget&) { return s.kiosk.operator_pin; },
         [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
             s.kiosk.operator_pin = v;
             return ok_status();
         }},
    };
}

std::vector<Field> tour_fields() {
    std::vector<Field> out = {
        // The tours array and each tour's steps change by the editor's commands (Add tour, + step, Remove).
        {"tours", "tours", FieldScope::Scene, FieldKind::Fixed,
         [](const Scene& s, const FieldTarget&) { return std::to_string(s.tours.size()); },
         [](Scene&, const FieldTarget&, const std::string&) -> Status {
             return input_error("tours: use Add tour / Remove");
         }},
        {"tours[].name", "tour name", FieldScope::Tour, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return tour(s, t).name; },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             if (s.kiosk.attract_tour == tour(s, t).name) s.kiosk.attract_tour = v;  // follows the rename
             tour(s, t).name = v;
             return ok_status();
         }},
        {"tours[].title", "tour title", FieldScope::TourTitle, FieldKind::Text,
         [](const Scene& s, const FieldTarget& t) { return title_of(tour(s, t).title, t); },
         [](Scene& s, const FieldTarget& t, const std::string& v) -> Status {
             set_text(tour(s, t).title, t.language, v);
             return ok_status();
         }},
        {"tours[].steps", "steps", FieldScope::Tour, FieldKind::Fixed,
         [](const Scene& s, const FieldTarget& t) { return std::to_string(tour(s, t).steps.size()); },
         [](Scene&, const FieldTarget&, const std::string&) -> Status {
             return input_error("steps: use + step from the view / Remove");
         }},
    };
    for (Field& f : step_fields()) out.push_back(f);
    return out;
}

void rename_in_tours(Scene& s, const std::string& from, const std::string& to) {
    for (scene::Tour& t : s.tours) {
        for (scene::TourStep& st : t.steps) {
            if (st.visible)
                for (std::string& n : *st.visible)
                    if (n == from) n = to;
            for (auto& [name, style] : st.styles)
                if (name == from) name = to;
            if (st.select == from) st.select = to;
        }
    }
}

void drop_tour_languages(Scene& s, const std::vector<std::string>& languages) {
    const auto gone = [&](const scene::LabelText& l) {
        return std::find(languages.begin(), languages.end(), l.language) == languages.end();
    };
    for (scene::Model& m : s.models) {
        for (scene::Pin& p : m.pins) {
            std::erase_if(p.labels, gone);
            if (p.labels.empty()) p.labels.push_back(scene::LabelText{languages.front(), m.name, ""});
        }
    }
    for (scene::Tour& t : s.tours) {
        std::erase_if(t.title, gone);
        for (scene::TourStep& st : t.steps) std::erase_if(st.caption, gone);
    }
}

}  // namespace body::kiosk::author::detail
