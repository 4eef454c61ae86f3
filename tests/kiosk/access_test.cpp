// The access modes (kiosk/app/access.h) through KioskApp: the visitors'
// toggles, the reset back to the manifest's modes, large text's bigger
// buttons, icons before the words, the operator's language set, and the
// scene keys' checks.
#include "kiosk/app/access.h"

#include <gtest/gtest.h>

#include "kiosk/app/kiosk_app.h"
#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

using test::replay;

KioskApp make(const std::string& kiosk) {
    auto scene =
        scene::parse_scene(R"({"models": [{"name": "a", "file": "a.obj"}], "kiosk": )" + kiosk + "}", "ac.json", "");
    EXPECT_TRUE(scene) << scene.error().message;
    return KioskApp(std::move(scene).value(), {ModelInfo{true, {0, 0, 0}, 40.0f, 1000, 100}}, 1280, 800);
}

const Control* find(const KioskApp& app, ControlId id) {
    for (const Control& c : app.controls())
        if (c.id == id) return &c;
    return nullptr;
}

void tap(KioskApp& app, ControlId id, double t) {
    const Control* c = find(app, id);
    ASSERT_NE(c, nullptr);
    const std::string at = std::to_string(c->rect.x + c->rect.w / 2) + " " + std::to_string(c->rect.y + c->rect.h / 2);
    run_replay(app,
               replay(std::to_string(t) + " down 1 " + at + "\n" + std::to_string(t + 0.05) + " up 1 " + at + "\n"),
               60.0, t);
}

TEST(Access, VisitorsToggleBothModesAndAResetRestoresTheManifests) {
    KioskApp app = make(R"({"access_buttons": true, "large_text": true})");
    ASSERT_NE(find(app, ControlId::Contrast), nullptr);
    EXPECT_FALSE(app.high_contrast());
    EXPECT_TRUE(app.large_text());
    EXPECT_TRUE(find(app, ControlId::LargeText)->active);
    const float large = find(app, ControlId::Home)->rect.h;
    tap(app, ControlId::Contrast, 0.2);
    tap(app, ControlId::LargeText, 0.5);
    EXPECT_TRUE(app.high_contrast());
    EXPECT_FALSE(app.large_text());
    EXPECT_TRUE(find(app, ControlId::Contrast)->active);
    EXPECT_LT(find(app, ControlId::Home)->rect.h, large);  // buttons shrink back with the text
    app.reset();
    EXPECT_FALSE(app.high_contrast());
    EXPECT_TRUE(app.large_text());
}

TEST(Access, NoTogglesUnlessTheManifestAsksAndTheyNeverOverlapTheColumn) {
    EXPECT_EQ(find(make("{}"), ControlId::Contrast), nullptr);
    for (const char* language : {"en", "ar"}) {
        UiState s;
        s.language = language;
        std::vector<Control> controls = layout_controls(s);
        add_access_controls(s, controls);
        for (const Control& a : controls) {
            if (a.id != ControlId::Contrast && a.id != ControlId::LargeText) continue;
            EXPECT_GE(a.rect.w, min_target_px(s));
            for (const Control& b : controls) {
                if (&a == &b) continue;
                const bool overlap = a.rect.x < b.rect.x + b.rect.w && b.rect.x < a.rect.x + a.rect.w &&
                                     a.rect.y < b.rect.y + b.rect.h && b.rect.y < a.rect.y + a.rect.h;
                EXPECT_FALSE(overlap) << language << " " << b.text;
            }
        }
    }
}

TEST(Access, IconsComeBeforeTheWords) {
    KioskApp with = make(R"({"icons": true})"), without = make("{}");
    EXPECT_EQ(find(with, ControlId::Home)->text, "⌂ Home");
    EXPECT_EQ(find(with, ControlId::Cut)->text, "✂ " + find(without, ControlId::Cut)->text);
    EXPECT_EQ(find(without, ControlId::Home)->text, "Home");
    EXPECT_STREQ(control_icon(ControlId::Isolate, false), "");
}

TEST(Access, TheOperatorsLanguageSetFeedsTheLanguageButton) {
    KioskApp app = make(R"({"languages": ["de", "en"]})");
    const auto set = app.language_set();
    ASSERT_EQ(set.size(), 10u);  // the manifest's two, then the table's other eight
    EXPECT_EQ(set[0], (std::pair<std::string, bool>{"de", true}));
    EXPECT_EQ(set[2], (std::pair<std::string, bool>{"fr", false}));
    app.toggle_language("ja");
    EXPECT_EQ(app.scene().kiosk.languages, (std::vector<std::string>{"de", "en", "ja"}));
    app.next_language();
    app.next_language();
    EXPECT_EQ(app.language(), "ja");
    app.toggle_language("ja");  // the visitor's language goes: the first takes over
    EXPECT_EQ(app.language(), "de");
    app.toggle_language("en");
    app.toggle_language("de");  // the last one stays
    EXPECT_EQ(app.scene().kiosk.languages, (std::vector<std::string>{"de"}));
}

TEST(Access, SceneKeysMustBeTrueOrFalse) {
    auto bad = scene::parse_scene(R"({"models": [{"name": "a", "file": "a.obj"}], "kiosk": {"large_text": 1}})",
                                  "ac.json", "");
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("kiosk.large_text"), std::string::npos) << bad.error().message;
    EXPECT_NE(bad.error().message.find("true or false"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace body::kiosk
