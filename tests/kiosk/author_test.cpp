// The authoring mode without GL: the UTF-8 text field, the document's undo/redo
// and validation, scene.json written back, the editor driven by input events,
// and the schema walk: every key SCENE.md's table documents has an editor
// (kiosk/author/fields.h) that changes that key in the saved file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>

#include "kiosk/app/replay.h"
#include "kiosk/author/editor.h"
#include "shared/atomic_file.h"
#include "shared/scene/scene_write.h"
#include "tests/common/test_dir.h"
#include "tests/kiosk/editor_events.h"

namespace body::kiosk::author {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* kScene = R"({"models": [
    {"name": "a", "file": "a.obj", "group": "left", "colour": [0.2, 0.5, 0.9],
     "label": {"en": {"title": "Alpha", "description": "The left one"}, "de": "Alpha"},
     "pins": [{"anchor": [1, 2, 3], "label": {"en": "Tip", "de": {"title": "Spitze", "description": "vorn"}}}]},
    {"name": "b", "file": "b.obj", "style": "wireframe", "lod": 0.5}],
  "groups": [{"name": "left", "style": "smooth"}, {"name": "right", "visible": false}],
  "kiosk": {"languages": ["en", "de"]},
  "tours": [{"name": "t1", "title": {"en": "Tour", "de": "Rundgang"},
             "steps": [{"caption": {"en": "Hi", "de": "Hallo"}}, {"select": "b"}]}]})";

scene::Scene test_scene() {
    auto s = scene::parse_scene(kScene, "scene.json", "");
    EXPECT_TRUE(s) << (s ? "" : s.error().message);
    return s.value();
}

json saved_json(Document& doc, const fs::path& path) {
    EXPECT_TRUE(doc.save(path.string())) << path;
    auto text = read_file(path.string());
    return json::parse(text.value());
}

TEST(AuthorTextField, EditsUtf8ByCodepoint) {
    TextField f;
    for (char32_t c : std::u32string(U"Grüße 😀")) f.insert(c);
    EXPECT_EQ(f.text(), "Grüße 😀");
    f.backspace();  // the emoji's four bytes go at once
    EXPECT_EQ(f.text(), "Grüße ");
    f.left(false);
    f.left(false);
    f.left(true);  // selects "ß"
    EXPECT_EQ(f.selected(), "ß");
    f.insert(U's');
    f.insert(U's');
    EXPECT_EQ(f.text(), "Grüsse ");
    f.home(false);
    f.right(true);
    f.right(true);
    f.right(true);
    EXPECT_EQ(f.selected(), "Grü");
    f.erase_forward();
    EXPECT_EQ(f.text(), "sse ");
    f.set_cursor(1, false);
    f.insert(std::string("€"));
    EXPECT_EQ(f.text(), "s€se ");
    f.set_cursor(2, false);  // inside "€": moved back to its first byte
    EXPECT_EQ(f.cursor(), 1u);
    f.insert(U'\n');  // control characters are not text
    EXPECT_EQ(f.text(), "s€se ");
    f.select_all();
    f.insert(U'x');
    EXPECT_EQ(f.text(), "x");
}

TEST(AuthorReplayFormat, TypedCharactersAreCodepoints) {
    auto r = parse_replay("0.1 text 252\n0.2 key 257 shift\n", "t.replay");
    ASSERT_TRUE(r) << r.error().message;
    ASSERT_EQ(r.value().events.size(), 2u);
    EXPECT_EQ(r.value().events[0].type, InputEvent::Type::Text);
    EXPECT_EQ(r.value().events[0].key, 252);
    EXPECT_EQ(r.value().events[1].key, platform::kKeyBackspace);
    EXPECT_EQ(r.value().events[1].modifiers, static_cast<uint32_t>(kModShift));
    auto bad = parse_replay("0.1 text -5\n", "t.replay");
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("t.replay: line 1"), std::string::npos) << bad.error().message;
    EXPECT_FALSE(parse_replay(R"({"events": [{"t": 0, "type": "text", "key": 55296}]})", "t.json"));
}

TEST(AuthorDocument, UndoRedoAndRefusedEdits) {
    Document doc(test_scene(), "");
    EXPECT_FALSE(doc.dirty());
    ASSERT_TRUE(doc.apply("style", [](scene::Scene& s) {
        s.models[0].style = Style::Hatching;
        return ok_status();
    }));
    EXPECT_TRUE(doc.dirty());
    // A duplicate name is what the parser refuses: nothing changes, the reason is the parser's.
    auto bad = doc.apply("rename", [](scene::Scene& s) {
        s.models[1].name = "a";
        return ok_status();
    });
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("duplicate model 'a'"), std::string::npos) << bad.error().message;
    EXPECT_EQ(doc.scene().models[1].name, "b");
    // Two nudges with one merge key are one step.
    for (int i = 0; i < 2; ++i)
        ASSERT_TRUE(doc.apply(
            "nudge",
            [](scene::Scene& s) {
                s.models[1].transform.translate[0] += 1.0f;
                return ok_status();
            },
            "nudge b"));
    EXPECT_EQ(doc.scene().models[1].transform.translate[0], 2.0f);
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(doc.scene().models[1].transform.translate[0], 0.0f);
    ASSERT_TRUE(doc.undo());
    EXPECT_EQ(doc.scene().models[0].style, Style::Smooth);
    EXPECT_FALSE(doc.dirty());  // back to what was loaded
    EXPECT_FALSE(doc.undo());
    ASSERT_TRUE(doc.redo());
    EXPECT_EQ(doc.scene().models[0].style, Style::Hatching);
    EXPECT_TRUE(doc.dirty());
    // An edit after an undo drops the redo branch.
    ASSERT_TRUE(doc.apply("lod", [](scene::Scene& s) {
        s.models[0].lod = scene::Lod{false, 0.25f};
        return ok_status();
    }));
    EXPECT_FALSE(doc.can_redo());
}

TEST(AuthorDocument, SavesTheSameSchemaAndReadsBackEqual) {
    const fs::path dir = test::fresh_test_dir("body_author");
    Document doc(test_scene(), (dir / "scene.json").string());
    const json j = saved_json(doc, dir / "scene.json");
    EXPECT_FALSE(doc.dirty());
    EXPECT_EQ(j["models"][0]["colour"], json::parse("[0.2, 0.5, 0.9]"));  // floats written as typed
    EXPECT_EQ(j["models"][1]["lod"], 0.5);
    EXPECT_EQ(j["models"][0]["label"]["de"]["title"], "Alpha");
    auto again = scene::read_scene((dir / "scene.json").string());
    ASSERT_TRUE(again) << again.error().message;
    EXPECT_EQ(scene::scene_to_json(again.value()), scene::scene_to_json(doc.scene()));
    // An invalid scene is never written: the old file stays.
    scene::Scene broken = doc.scene();
    broken.models[0].group = "nowhere";
    EXPECT_FALSE(scene::save_scene(broken, (dir / "scene.json").string()));
    EXPECT_TRUE(scene::read_scene((dir / "scene.json").string()));
    fs::remove_all(dir);
}

// A scene using every key of SCENE.md's tables, with values other than the defaults
// and in the forms the writer writes (labels as objects, titles and captions as text).
const char* kEveryKey = R"({"version": 1,
  "models": [
    {"name": "a", "file": "a.obj", "group": "left", "colour": [0.1, 0.2, 0.3],
     "transform": {"translate": [1, 2, 3], "rotate_deg": [10, 20, 30], "scale": 2},
     "style": "hatching", "lod": 0.5,
     "label": {"en": {"title": "A", "description": "Alpha"}, "de": {"title": "A-de", "description": ""}},
     "pins": [{"anchor": [0.5, -1.25, 3], "label": {"en": {"title": "Tip", "description": "The tip"},
                                                    "de": {"title": "Spitze", "description": ""}}},
              {"anchor": [0, 0, 0], "label": {"de": {"title": "Basis", "description": "unten"}}}]},
    {"name": "b", "file": "b.obj", "style": "hatching-2tone", "lod": "auto",
     "label": {"en": {"title": "B", "description": ""}}}],
  "groups": [{"name": "left", "style": "lines", "lod": "auto", "visible": false}, {"name": "right", "lod": 0.25, "visible": true}],
  "camera": {"target": [4, 5, 6], "azimuth_deg": 30, "polar_deg": 70, "distance": 400, "fov_deg": 35},
  "kiosk": {"idle_seconds": 20, "reset_seconds": 90, "languages": ["en", "de"],
            "admin_gesture": {"corner": "bottom-right", "taps": 4, "seconds": 2.5, "corner_size": 0.1},
            "frame_ms_target": 33, "attract_tour": "limbic", "countdown_seconds": 15, "pins": true,
            "operator_pin": "004217", "high_contrast": true, "large_text": true, "access_buttons": true,
            "icons": true},
  "cut_plane": {"axial": [0, 0, 1], "coronal": [0, 1, 0], "sagittal": [-1, 0, 0.5],
                "slices": [-2, 0.5, 3], "slice_normal": [0, 0, 2], "volume": "slices.vol",
                "volume_around": true},
  "tours": [
    {"name": "limbic", "title": {"en": "The limbic system", "de": "Das limbische System"},
     "steps": [
       {"camera": {"target": [1, 2, 3], "azimuth_deg": 90, "polar_deg": 70, "distance": 250},
        "visible": ["left", "b"], "styles": {"left": "hatching", "b": "wireframe"}, "select": "a",
        "caption": {"en": "Seen from the right", "de": "Von rechts"}, "duration": 1.5, "hold": 5, "easing": "linear"},
       {"camera": {"azimuth_deg": -45}, "duration": 0, "hold": 3600, "easing": "ease-in",
        "cut": {"axis": "coronal", "offset": -2.5}}]},
    {"name": "second", "steps": [{"visible": [], "duration": 2, "hold": 4, "easing": "ease-out",
                                  "cut": {"normal": [0, 1, 0.5], "offset": 3}}]}]})";

// Every value of `expected` is in `actual` at the same place (`actual` may add defaults).
void expect_contains(const json& actual, const json& expected, const std::string& path) {
    if (expected.is_object()) {
        ASSERT_TRUE(actual.is_object()) << path;
        for (const auto& [k, v] : expected.items()) {
            EXPECT_TRUE(actual.contains(k)) << path << "." << k << " was dropped";
            if (actual.contains(k)) expect_contains(actual[k], v, path + "." + k);
        }
    } else if (expected.is_array()) {
        ASSERT_TRUE(actual.is_array()) << path;
        ASSERT_EQ(actual.size(), expected.size()) << path;
        for (size_t i = 0; i < expected.size(); ++i)
            expect_contains(actual[i], expected[i], path + "[" + std::to_string(i) + "]");
    } else {
        EXPECT_EQ(actual, expected) << path;
    }
}

TEST(AuthorSchema, EveryKeyRoundTrips) {
    auto first = scene::parse_scene(kEveryKey, "every.json", "");
    ASSERT_TRUE(first) << first.error().message;
    const std::string text = scene::scene_to_json(first.value());
    expect_contains(json::parse(text), json::parse(kEveryKey), "$");
    auto second = scene::parse_scene(text, "written.json", "");
    ASSERT_TRUE(second) << second.error().message;
    EXPECT_EQ(scene::scene_to_json(second.value()), text);  // write -> parse -> write: the same text
    // The values read back, field by field, for the keys added with tours and pins.
    const scene::Scene &a = first.value(), &b = second.value();
    EXPECT_EQ(b.kiosk.attract_tour, "limbic");
    EXPECT_EQ(b.kiosk.countdown_seconds, a.kiosk.countdown_seconds);
    EXPECT_TRUE(b.kiosk.pins);
    EXPECT_EQ(b.kiosk.operator_pin, "004217");  // leading zeros kept: a string, not a number
    EXPECT_EQ(b.cut_plane.slices, (std::vector<float>{-2.0f, 0.5f, 3.0f}));
    EXPECT_EQ(b.cut_plane.slice_normal, (std::array<float, 3>{0.0f, 0.0f, 2.0f}));
    EXPECT_EQ(b.cut_plane.volume, "slices.vol");
    EXPECT_TRUE(b.cut_plane.volume_around);
    ASSERT_EQ(b.models[0].pins.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(b.models[0].pins[i].anchor, a.models[0].pins[i].anchor);
        ASSERT_EQ(b.models[0].pins[i].labels.size(), a.models[0].pins[i].labels.size());
        for (size_t k = 0; k < a.models[0].pins[i].labels.size(); ++k) {
            EXPECT_EQ(b.models[0].pins[i].labels[k].title, a.models[0].pins[i].labels[k].title);
            EXPECT_EQ(b.models[0].pins[i].labels[k].description, a.models[0].pins[i].labels[k].description);
        }
    }
    ASSERT_EQ(b.tours.size(), 2u);
    for (size_t t = 0; t < 2; ++t) {
        EXPECT_EQ(b.tours[t].name, a.tours[t].name);
        EXPECT_EQ(b.tours[t].title.size(), a.tours[t].title.size());
        ASSERT_EQ(b.tours[t].steps.size(), a.tours[t].steps.size());
        for (size_t k = 0; k < a.tours[t].steps.size(); ++k) {
            const scene::TourStep &x = a.tours[t].steps[k], &y = b.tours[t].steps[k];
            EXPECT_EQ(y.camera.target, x.camera.target);
            EXPECT_EQ(y.camera.azimuth_deg, x.camera.azimuth_deg);
            EXPECT_EQ(y.camera.polar_deg, x.camera.polar_deg);
            EXPECT_EQ(y.camera.distance, x.camera.distance);
            EXPECT_EQ(y.visible, x.visible);  // [] (hide all) stays apart from absent (as before the tour)
            EXPECT_EQ(y.styles, x.styles);
            EXPECT_EQ(y.select, x.select);
            ASSERT_EQ(y.caption.size(), x.caption.size());
            for (size_t c = 0; c < x.caption.size(); ++c) EXPECT_EQ(y.caption[c].title, x.caption[c].title);
            EXPECT_EQ(y.duration, x.duration);
            ASSERT_EQ(y.cut.has_value(), x.cut.has_value());
            if (x.cut) {
                EXPECT_EQ(y.cut->axis, x.cut->axis);
                EXPECT_EQ(y.cut->normal, x.cut->normal);
                EXPECT_EQ(y.cut->offset, x.cut->offset);
            }
            EXPECT_EQ(y.hold, x.hold);
            EXPECT_EQ(y.easing, x.easing);
        }
    }
    EXPECT_FALSE(b.tours[0].steps[1].camera.target);  // unset camera values stay unset
    EXPECT_FALSE(b.tours[1].steps[0].camera.azimuth_deg);
}

// The keys SCENE.md's table documents: the one place the schema is written down
// (helpers adding keys document them there), read fresh by this test.
std::set<std::string> documented_keys() {
    std::ifstream in(std::string(BODY_SOURCE_DIR) + "/shared/scene/SCENE.md");
    EXPECT_TRUE(in) << "shared/scene/SCENE.md";
    std::set<std::string> keys;
    const std::regex row(R"(^\| `([^`]+)` \|)");
    std::smatch m;
    for (std::string line; std::getline(in, line);)
        if (std::regex_search(line, m, row)) keys.insert(m[1]);
    return keys;
}

// A new valid value for each editor, by its panel label: a field added without
// one here fails the walk below, so its editor gets tested.
const std::map<std::string, std::string> kNewValues = {
    {"name", "renamed"},
    {"file", "c.obj"},
    {"colour", "1 0 0.5"},
    {"translate", "1 2 3"},
    {"rotate (deg)", "10 20 30"},
    {"scale", "2"},
    {"title", "Titel"},
    {"description", "Beschreibung"},
    {"camera target", "1 2 3"},
    {"camera azimuth", "45"},
    {"camera polar", "60"},
    {"camera distance", "500"},
    {"camera fov", "30"},
    {"cut axial normal", "0 0 1"},
    {"cut coronal normal", "0 1 0"},
    {"cut sagittal normal", "-1 0 0.5"},
    {"idle (s)", "20"},
    {"reset (s)", "90"},
    {"languages", "en fr"},
    {"admin taps", "7"},
    {"admin seconds", "4"},
    {"admin corner size", "0.1"},
    {"frame target (ms)", "33"},
    {"countdown (s)", "5"},
    {"operator PIN", "1234"},
    {"pin anchor", "4 5 6"},
    {"pin title", "Spitzen"},
    {"pin description", "hinten"},
    {"tour name", "t2"},
    {"tour title", "Führung"},
    {"step target", "1 2 3"},
    {"step azimuth", "45"},
    {"step polar", "60"},
    {"step distance", "300"},
    {"step visible", "b, right"},
    {"step styles", "a=hatching, left=lines"},
    {"caption", "Beschriftung"},
    {"duration (s)", "3"},
    {"hold (s)", "6"},
    {"step cut", "coronal -5"},
    {"cut slice normal", "0 0 2"},
    {"cut slices", "1 2.5 4"},
    {"cut slices volume", "grey/ch2.vol"},
};

// A table key as the saved JSON nests it: a tour's steps are inside tours[].
std::string json_key(const std::string& key) { return key.starts_with("steps[].") ? "tours[]." + key : key; }

// The saved JSON at a table key ("models[].colour" -> models[0].colour).
json at_key(const json& root, const std::string& key) {
    json v = root;
    std::string k = json_key(key);
    for (size_t dot; !k.empty(); k = dot == std::string::npos ? "" : k.substr(dot + 1)) {
        dot = k.find('.');
        std::string part = k.substr(0, dot);
        const bool array = part.size() > 2 && part.ends_with("[]");
        if (array) part.resize(part.size() - 2);
        if (!v.contains(part)) return json();
        v = v[part];
        if (array) v = v[0];
    }
    return v;
}

TEST(AuthorSchema, EveryDocumentedKeyHasAnEditorThatChangesIt) {
    const std::set<std::string> keys = documented_keys();
    ASSERT_GT(keys.size(), 20u);
    std::set<std::string> edited;
    for (const Field& f : scene_fields()) {
        EXPECT_TRUE(keys.count(f.key)) << "editor for '" << f.key << "', which SCENE.md's table does not list";
        edited.insert(f.key);
    }
    for (const std::string& k : keys)
        EXPECT_TRUE(edited.count(k)) << "scene.json key '" << k
                                     << "' has no editor in kiosk/author/fields.cpp (add one to scene_fields())";

    const fs::path dir = test::fresh_test_dir("body_author");
    for (size_t i = 0; i < scene_fields().size(); ++i) {
        const Field& f = scene_fields()[i];
        Document doc(test_scene(), (dir / "scene.json").string());
        const json before = saved_json(doc, dir / "scene.json");
        using S = FieldScope;
        FieldTarget t;
        const bool pin = f.scope == S::Pin || f.scope == S::PinLabel;
        t.model = f.scope == S::Model || f.scope == S::Label || pin ? 0 : -1;
        t.pin = pin ? 0 : -1;
        t.group = f.scope == S::Group ? 0 : -1;
        t.tour =
            f.scope == S::Tour || f.scope == S::TourTitle || f.scope == S::Step || f.scope == S::StepCaption ? 0 : -1;
        t.step = f.scope == S::Step || f.scope == S::StepCaption ? 0 : -1;
        const bool text =
            f.scope == S::Label || f.scope == S::PinLabel || f.scope == S::TourTitle || f.scope == S::StepCaption;
        t.language = text ? "de" : "";
        if (f.kind == FieldKind::Fixed) {
            const json b = at_key(before, f.key);
            EXPECT_EQ(f.get(doc.scene(), t), b.is_array() ? std::to_string(b.size()) : b.dump()) << f.key;
            continue;  // `version` is always 1; `models`, `tours`, steps: add/remove commands (Editor tests below)
        }
        std::string value;
        if (f.kind == FieldKind::Choice) {
            value = next_choice(f.choices(doc.scene()), f.get(doc.scene(), t));
        } else {
            auto it = kNewValues.find(f.label);
            ASSERT_NE(it, kNewValues.end()) << "no test value for the editor '" << f.label << "' (" << f.key << ")";
            value = it->second;
        }
        auto s = doc.apply("set", [&](scene::Scene& sc) { return f.set(sc, t, value); });
        ASSERT_TRUE(s) << f.key << " = " << value << ": " << s.error().message;
        EXPECT_EQ(f.get(doc.scene(), t), value) << f.key;
        const json after = saved_json(doc, dir / "scene.json");
        EXPECT_NE(at_key(after, f.key), at_key(before, f.key)) << f.key << " (" << f.label << ") = " << value;
        EXPECT_TRUE(scene::read_scene((dir / "scene.json").string())) << f.key;
    }
    fs::remove_all(dir);
}

// Every key the writer puts in scene.json is a documented one (or inside one:
// `transform`, `label`, `admin_gesture` are documented as objects).
void collect(const json& v, const std::string& path, std::set<std::string>& out) {
    if (v.is_array()) {
        for (const json& e : v) collect(e, path + "[]", out);
    } else if (v.is_object()) {
        for (const auto& [k, e] : v.items()) {
            const std::string p = path.empty() ? k : path + "." + k;
            out.insert(p);
            collect(e, p, out);
        }
    }
}

TEST(AuthorSchema, TheWriterWritesOnlyDocumentedKeys) {
    const std::set<std::string> keys = documented_keys();
    std::set<std::string> written;
    collect(json::parse(scene::scene_to_json(test_scene())), "", written);
    for (const std::string& w : written) {
        bool documented = false;
        for (const std::string& k : keys)  // a container of documented keys (`camera`, `groups`)
            documented = documented || k.starts_with(w + ".") || k.starts_with(w + "[].");
        for (std::string p = w.starts_with("tours[].steps[].") ? w.substr(8) : w; !documented && !p.empty();) {
            documented = keys.count(p) > 0 || (p.ends_with("[]") && keys.count(p.substr(0, p.size() - 2)) > 0);
            const size_t dot = p.rfind('.');
            p = dot == std::string::npos ? "" : p.substr(0, dot);
        }
        EXPECT_TRUE(documented) << "scene_to_json writes '" << w << "', which SCENE.md's table does not list";
    }
    EXPECT_TRUE(written.count("models[].transform.rotate_deg"));
}

// kEveryKey uses every documented key: a key added to SCENE.md without a place in it fails
// here, so the round trip above covers it.
TEST(AuthorSchema, TheRoundTripSceneUsesEveryDocumentedKey) {
    std::set<std::string> written;
    collect(json::parse(kEveryKey), "", written);
    for (const std::string& k : documented_keys())
        EXPECT_TRUE(written.count(json_key(k))) << "kEveryKey (author_test.cpp) does not use '" << k << "'";
}

// --- the editor driven by events, as the window feeds it ---------------------

using events::click;
using events::key;
using events::type;

TEST(AuthorEditor, PanelEditsUndoRedoSaveAndAddRemove) {
    const fs::path dir = test::fresh_test_dir("body_author");
    std::ofstream(dir / "c.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    Editor ed(Document(test_scene(), (dir / "scene.json").string()));
    ed.set_viewport(1280, 800, 1.0f);
    click(ed, "▸ left (1)");  // opens the group: its model is listed
    click(ed, "a");
    ASSERT_EQ(ed.selection().model, 0);
    click(ed, "style");  // a choice: smooth -> wireframe
    EXPECT_EQ(ed.document().scene().models[0].style, Style::Wireframe);
    click(ed, "title [de]");
    ed.handle(key('A', kModCtrl));
    type(ed, U"Großhirn");
    ed.handle(key(platform::kKeyEnter));
    EXPECT_EQ(ed.document().scene().label(ed.document().scene().models[0], "de").title, "Großhirn");
    click(ed, "scale");
    ed.handle(key('A', kModCtrl));
    type(ed, U"-1");  // out of range: refused, the field keeps the focus and the status says why
    ed.handle(key(platform::kKeyEnter));
    EXPECT_NE(ed.status().find("scale"), std::string::npos) << ed.status();
    EXPECT_EQ(ed.document().scene().models[0].transform.scale, 1.0f);
    ed.handle(key(platform::kKeyEscape));
    ed.handle(key('Z', kModCtrl));  // undo the title
    EXPECT_EQ(ed.document().scene().label(ed.document().scene().models[0], "de").title, "Alpha");
    ed.handle(key('Z', kModCtrl | kModShift));  // redo it
    EXPECT_EQ(ed.document().scene().label(ed.document().scene().models[0], "de").title, "Großhirn");
    click(ed, "add model (.bpm/.obj/.stl/.ply)");
    type(ed, U"" + std::u32string((dir / "c.obj").u32string()));
    ed.handle(key(platform::kKeyEnter));
    ASSERT_EQ(ed.document().scene().models.size(), 3u) << ed.status();
    EXPECT_EQ(ed.document().scene().models[2].file, "c.obj");  // relative to the manifest
    EXPECT_EQ(ed.selection().model, 2);
    ed.handle(key(platform::kKeyDelete));
    ASSERT_EQ(ed.document().scene().models.size(), 2u);
    ed.handle(key('S', kModCtrl));
    EXPECT_FALSE(ed.document().dirty()) << ed.status();
    const json j = json::parse(read_file((dir / "scene.json").string()).value());
    EXPECT_EQ(j["models"][0]["style"], "wireframe");
    EXPECT_EQ(j["models"][0]["label"]["de"]["title"], "Großhirn");
    EXPECT_EQ(j["models"].size(), 2u);
    fs::remove_all(dir);
}

TEST(AuthorEditor, UnsavedChangesPromptOnQuit) {
    const fs::path dir = test::fresh_test_dir("body_author");
    Editor ed(Document(test_scene(), (dir / "scene.json").string()));
    ed.set_viewport(1280, 800, 1.0f);
    ed.request_quit();  // clean: quits at once
    EXPECT_TRUE(ed.quit_confirmed());

    Editor dirty(Document(test_scene(), (dir / "scene.json").string()));
    dirty.set_viewport(1280, 800, 1.0f);
    click(dirty, "b");
    click(dirty, "LOD");
    dirty.handle(key('Q', kModCtrl));
    EXPECT_TRUE(dirty.prompt_visible());
    EXPECT_FALSE(dirty.quit_confirmed());
    dirty.handle(key(platform::kKeyEscape));  // back to editing
    EXPECT_FALSE(dirty.prompt_visible());
    dirty.handle(key('Q', kModCtrl));
    dirty.handle(key('S'));  // save and quit
    EXPECT_TRUE(dirty.quit_confirmed());
    EXPECT_TRUE(fs::exists(dir / "scene.json"));
    fs::remove_all(dir);
}

// Pins, tours and steps through the editor's commands: each one undo step.
TEST(AuthorEditor, PinsToursAndStepsAreUndoableCommands) {
    Editor ed(Document(test_scene(), ""));
    ed.set_viewport(1280, 800, 1.0f);
    // Add pin needs a clicked surface point on the selected model.
    click(ed, "b");
    click(ed, "Add pin at the clicked point");
    EXPECT_TRUE(ed.document().scene().models[1].pins.empty()) << ed.status();
    ed.set_surface_point(1, {0.5f, 0.25f, -1.0f});
    click(ed, "Add pin at the clicked point");
    ASSERT_EQ(ed.document().scene().models[1].pins.size(), 1u) << ed.status();
    EXPECT_EQ(ed.document().scene().models[1].pins[0].anchor, (std::array<float, 3>{0.5f, 0.25f, -1.0f}));
    click(ed, "pin title #1 [de]");
    type(ed, U"Knoten");
    ed.handle(key(platform::kKeyEnter));
    EXPECT_EQ(ed.document().scene().text(ed.document().scene().models[1].pins[0].labels, "de")->title, "Knoten");
    click(ed, "Remove pin #1");
    EXPECT_TRUE(ed.document().scene().models[1].pins.empty());
    ed.handle(key('Z', kModCtrl));  // the removal undone: the pin is back with its title
    ASSERT_EQ(ed.document().scene().models[1].pins.size(), 1u);

    // A step from the view: camera, visible models and the model selected (b) at the click.
    click(ed, "b");
    click(ed, "+ step to t1 from the view");
    ASSERT_EQ(ed.take_request(), Request::AddStep);
    scene::HomeCamera cam;
    cam.target = {1, 2, 3};
    cam.azimuth_deg = 45;
    cam.polar_deg = 80;
    cam.distance = 120;
    ASSERT_TRUE(ed.add_step(ed.step_request_tour(), cam, {"a"}));
    const auto& steps = [&]() -> const std::vector<scene::TourStep>& { return ed.document().scene().tours[0].steps; };
    ASSERT_EQ(steps().size(), 3u);
    EXPECT_EQ(steps()[2].camera.azimuth_deg, 45.0f);
    EXPECT_EQ(steps()[2].camera.target, (std::array<float, 3>{1, 2, 3}));
    EXPECT_EQ(steps()[2].visible, (std::vector<std::string>{"a"}));
    EXPECT_EQ(steps()[2].select, "b");
    EXPECT_EQ(ed.selection().tour, 0);
    EXPECT_EQ(ed.selection().step, 2);
    click(ed, "easing");  // ease-in-out -> linear
    EXPECT_EQ(steps()[2].easing, scene::Easing::Linear);
    click(ed, "Step earlier");
    EXPECT_EQ(steps()[1].select, "b");
    EXPECT_EQ(steps()[2].select, "b");  // the old step 2 selected b too
    EXPECT_EQ(steps()[1].camera.azimuth_deg, 45.0f);
    EXPECT_EQ(ed.selection().step, 1);
    ed.handle(key(platform::kKeyDelete));  // removes the selected step
    ASSERT_EQ(steps().size(), 2u);
    EXPECT_FALSE(steps()[1].camera.azimuth_deg);

    // Renaming a model renames it in the steps; dropping a language drops its captions and pin texts.
    ed.select_model(1);
    click(ed, "name");
    ed.handle(key('A', kModCtrl));
    type(ed, U"bee");
    ed.handle(key(platform::kKeyEnter));
    EXPECT_EQ(steps()[1].select, "bee") << ed.status();
    ed.handle(key(platform::kKeyEscape));  // deselects: the scene's fields
    click(ed, "languages");
    ed.handle(key('A', kModCtrl));
    type(ed, U"en");
    ed.handle(key(platform::kKeyEnter));
    ASSERT_EQ(ed.document().scene().kiosk.languages.size(), 1u) << ed.status();
    EXPECT_EQ(ed.document().scene().tours[0].steps[0].caption.size(), 1u);
    EXPECT_EQ(ed.document().scene().models[0].pins[0].labels.size(), 1u);
    EXPECT_EQ(ed.document().scene().models[1].pins[0].labels[0].language, "en");  // its "de" title went

    // A new tour, the attract tour, then the tour removed: the attract mode turns again.
    click(ed, "Add tour");
    ASSERT_EQ(ed.document().scene().tours.size(), 2u) << ed.status();
    EXPECT_EQ(ed.document().scene().tours[1].name, "tour 1");
    ed.handle(key(platform::kKeyEscape));
    click(ed, "attract tour");  // none -> t1
    click(ed, "attract tour");  // -> tour 1
    EXPECT_EQ(ed.document().scene().kiosk.attract_tour, "tour 1");
    click(ed, "▸ tour 1 (1 steps)");
    ed.handle(key(platform::kKeyDelete));
    EXPECT_EQ(ed.document().scene().tours.size(), 1u);
    EXPECT_TRUE(ed.document().scene().kiosk.attract_tour.empty());
    // A tour keeps its last step: the parser's reason, nothing changed.
    click(ed, "▸ t1 (2 steps)");
    click(ed, "step 2");
    ed.handle(key(platform::kKeyDelete));
    click(ed, "step 1");
    ed.handle(key(platform::kKeyDelete));
    EXPECT_EQ(ed.document().scene().tours[0].steps.size(), 1u);
    EXPECT_NE(ed.status().find("non-empty"), std::string::npos) << ed.status();
    // Everything above is undoable back to the scene loaded.
    while (ed.document().undo()) {
    }
    EXPECT_FALSE(ed.document().dirty());
    // A selection an undo took away removes nothing (and does not throw).
    ASSERT_TRUE(ed.add_tour());
    ASSERT_EQ(ed.selection().tour, 1);
    ed.handle(key('Z', kModCtrl));
    ed.handle(key(platform::kKeyDelete));
    click(ed, "Add tour");
    EXPECT_EQ(ed.document().scene().tours.size(), 2u);
    ed.select_tour(1, 0);
    ed.handle(key('Z', kModCtrl));
    EXPECT_FALSE(ed.move_step(-1));
    ed.handle(key(platform::kKeyDelete));
    EXPECT_EQ(ed.document().scene().tours.size(), 1u);
}

}  // namespace
}  // namespace body::kiosk::author
