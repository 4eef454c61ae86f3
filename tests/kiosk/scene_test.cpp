// scene.json: a valid manifest parses with defaults and overrides; each kind of
// mistake is rejected with the file and JSON path in the message.
#include "shared/scene/scene.h"

#include <gtest/gtest.h>

namespace body::scene {
namespace {

const char* kScene = R"json({
  "version": 1,
  "models": [
    {"name": "hippo", "file": "m/hippo.bpm", "group": "limbic", "colour": [1, 0.5, 0.25],
     "transform": {"translate": [1, 2, 3], "scale": 2}, "style": "hatching", "lod": 0.5,
     "label": {"en": {"title": "Hippocampus", "description": "Memory"}, "de": "Hippocampus (de)"}},
    {"name": "cortex", "file": "cortex.obj"}
  ],
  "groups": [{"name": "limbic", "style": "lines", "lod": "auto", "visible": false}],
  "camera": {"target": [0, 1, 0], "azimuth_deg": 30, "polar_deg": 60, "distance": 500},
  "kiosk": {"idle_seconds": 10, "reset_seconds": 60, "languages": ["en", "de"],
            "admin_gesture": {"corner": "bottom-right", "taps": 4, "seconds": 2}}
})json";

TEST(Scene, ParsesEveryField) {
    auto s = parse_scene(kScene, "scene.json", "/bundle");
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_EQ(s->models.size(), 2u);
    const Model& m = s->models[0];
    EXPECT_EQ(m.path, "/bundle/m/hippo.bpm");
    EXPECT_EQ(m.group, "limbic");
    EXPECT_FLOAT_EQ(m.colour[1], 0.5f);
    EXPECT_FLOAT_EQ(m.transform.translate[2], 3.0f);
    EXPECT_FLOAT_EQ(m.transform.scale, 2.0f);
    EXPECT_EQ(m.style, Style::Hatching);
    EXPECT_FALSE(m.lod.automatic);
    EXPECT_FLOAT_EQ(m.lod.ratio, 0.5f);
    EXPECT_EQ(s->label(m, "de").title, "Hippocampus (de)");
    EXPECT_EQ(s->label(m, "fr").title, "Hippocampus");  // falls back to the first language
    EXPECT_EQ(s->label(m, "en").description, "Memory");
    const Model& c = s->models[1];
    EXPECT_EQ(c.style, Style::Smooth);
    EXPECT_TRUE(c.lod.automatic);
    EXPECT_EQ(s->label(c, "en").title, "cortex");  // no label: the name
    ASSERT_EQ(s->groups.size(), 1u);
    EXPECT_EQ(s->groups[0].style, Style::Lines);
    EXPECT_FALSE(s->groups[0].visible);
    EXPECT_FLOAT_EQ(s->camera.polar_deg, 60.0f);
    EXPECT_FLOAT_EQ(s->kiosk.idle_seconds, 10.0f);
    EXPECT_EQ(s->kiosk.admin.corner, AdminGesture::Corner::BottomRight);
    EXPECT_EQ(s->kiosk.admin.taps, 4);
    EXPECT_EQ(s->model_index("cortex"), 1);
}

std::string error_of(const std::string& text) {
    auto s = parse_scene(text, "scene.json", "");
    return s ? std::string("(parsed)") : s.error().message;
}

// Found by fuzz_scene_parser: nlohmann throws out_of_range (not parse_error) for 1e99999.
TEST(Scene, NumberOverflowIsAnErrorNotACrash) {
    auto s = parse_scene(R"({"version": 1, "models": [], "camera": {"fov_deg": 1e99999}})", "scene.json", "");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message.rfind("scene.json: not valid JSON: ", 0), 0u) << s.error().message;
}

// Found by fuzz_scene_parser: a value with a newline made the one-line error two lines.
TEST(Scene, ControlCharactersInAnErrorAreEscaped) {
    const std::string m =
        error_of(R"({"version": 1, "models": [{"name": "a", "file": "a.obj", "style": "hatch\ng"}]})");
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_NE(m.find("unknown style 'hatch\\x0ag'"), std::string::npos) << m;
    EXPECT_EQ(m.rfind("scene.json: models[0].style: ", 0), 0u) << m;
}

TEST(Scene, ErrorsNameFileAndPath) {
    EXPECT_EQ(error_of(R"({"models": [{"name": "a"}]})"), "scene.json: models[0].file: missing");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "colour": [1, 2, 0]}]})"),
              "scene.json: models[0].colour[1]: expected a number in [0, 1]");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "group": "nope"}]})"),
              "scene.json: models[0].group: no group named 'nope' in groups");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "colour": [1, 1, 1], "colr": 1}]})"),
              "scene.json: models[0].colr: unknown key");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj"}, {"name": "a", "file": "b.obj"}]})"),
              "scene.json: models[1].name: duplicate model 'a'");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "style": "cartoon"}]})"),
              "scene.json: models[0].style: unknown style 'cartoon' (wireframe, smooth, lines, hatching, "
              "hatching-2tone)");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "lod": 1.5}]})"),
              "scene.json: models[0].lod: expected \"auto\" or a ratio in (0, 1]");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj", "label": {"fr": "A"}}]})"),
              "scene.json: models[0].label.fr: language not listed in kiosk.languages");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj"}], "kiosk": {"idle_seconds": 50,
              "reset_seconds": 20}})"),
              "scene.json: kiosk.reset_seconds: must not be shorter than idle_seconds");
    EXPECT_EQ(error_of(R"({"models": []})"), "scene.json: models: expected a non-empty array");
    EXPECT_EQ(error_of(R"({"models": [}")"), "scene.json: byte 13: not valid JSON");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj"}], "camera": {"polar_deg": 0}})"),
              "scene.json: camera.polar_deg: expected a number in [1, 179]");
    EXPECT_EQ(error_of(R"({"models": [{"name": "a", "file": "a.obj"}],
              "kiosk": {"admin_gesture": {"corner": "middle"}}})"),
              "scene.json: kiosk.admin_gesture.corner: expected top-left, top-right, bottom-left or bottom-right");
}

// The places inside a model that is not the first (each one's path is made only when it fails).
TEST(Scene, ErrorsNameTheNestedPlaceInsideAModel) {
    const std::string first = R"({"name": "a", "file": "a.obj"}, )";
    auto model = [&](const std::string& rest) {
        return error_of(R"({"models": [)" + first + R"({"name": "b", "file": "b.obj", )" + rest + "}]}");
    };
    EXPECT_EQ(model(R"("transform": {"rotate_deg": [0, 0, 400]})"),
              "scene.json: models[1].transform.rotate_deg[2]: expected a number in [-360, 360]");
    EXPECT_EQ(model(R"("transform": {"translate": [0, "x", 0]})"),
              "scene.json: models[1].transform.translate[1]: expected a number");
    EXPECT_EQ(model(R"("transform": {"scale": 0})"),
              "scene.json: models[1].transform.scale: expected a number in [1e-06, 1e+06]");
    EXPECT_EQ(model(R"("transform": {"shear": 1})"), "scene.json: models[1].transform.shear: unknown key");
    EXPECT_EQ(model(R"("label": {"en": {"description": "d"}})"), "scene.json: models[1].label.en.title: missing");
    EXPECT_EQ(model(R"("label": {"en": {"title": ""}})"), "scene.json: models[1].label.en.title: must not be empty");
    EXPECT_EQ(model(R"("label": {"en": {"title": "t", "description": 3}})"),
              "scene.json: models[1].label.en.description: expected a string");
    EXPECT_EQ(model(R"("label": {"en": {"title": "t", "note": 3}})"),
              "scene.json: models[1].label.en.note: unknown key");
    EXPECT_EQ(model(R"("group": 7)"), "scene.json: models[1].group: expected a string");
    EXPECT_EQ(error_of(R"({"models": [)" + first + R"({"file": "b.obj"}]})"), "scene.json: models[1].name: missing");
}

// A model's file beside the manifest's folder, as std::filesystem joins them.
TEST(Scene, ModelFilesAreFoundBesideTheManifest) {
    const char* text = R"({"models": [{"name": "a", "file": "m/a.bpm"}, {"name": "b", "file": "/abs/b.bpm"}]})";
    for (const char* base : {"/bundle", "/bundle/"}) {
        auto s = parse_scene(text, "scene.json", base);
        ASSERT_TRUE(s) << s.error().message;
        EXPECT_EQ(s->models[0].path, "/bundle/m/a.bpm") << base;
        EXPECT_EQ(s->models[1].path, "/abs/b.bpm") << base;
    }
    auto s = parse_scene(text, "scene.json", "");
    ASSERT_TRUE(s) << s.error().message;
    EXPECT_EQ(s->models[0].path, "m/a.bpm");
    EXPECT_EQ(s->models[0].file, "m/a.bpm");
}

TEST(Scene, ReadSceneNamesAMissingFile) {
    auto s = read_scene("/nonexistent/scene.json");
    ASSERT_FALSE(s);
    EXPECT_NE(s.error().message.find("/nonexistent/scene.json"), std::string::npos);
}

TEST(Scene, StyleNamesRoundTrip) {
    for (int i = 0; i < kStyleCount; ++i) {
        const Style s = static_cast<Style>(i);
        EXPECT_EQ(parse_style(style_name(s)), s);
    }
    EXPECT_FALSE(parse_style("Smooth"));
}

}  // namespace
}  // namespace body::scene
