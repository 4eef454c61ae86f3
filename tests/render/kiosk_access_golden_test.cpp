// Golden pictures of the kiosk's access modes through bodyview (headless,
// llvmpipe, 800x500; kiosk/app/access.h): high contrast with a label card and
// pins, large text with icons, and the kiosk in a language the operator
// switched on. A visitor's tap on the contrast toggle gives the same picture
// as the manifest's high contrast. Taps are placed with the kiosk's own layout
// functions. BODY_UPDATE_GOLDENS=1 rewrites tests/render/golden/.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "kiosk/app/access.h"
#include "kiosk/app/operator_mode.h"
#include "kiosk/render/image.h"
#include "shared/obj_io.h"
#include "tests/common/test_meshes.h"
#include "tests/render/kiosk_golden.h"
#include "tests/render/render_fixture.h"

namespace body {
namespace {

namespace fs = std::filesystem;
using kiosk::ControlId;
using test::tap_at;
constexpr int kWidth = test::kGoldenWidth, kHeight = test::kGoldenHeight;

const kiosk::Control* find(const std::vector<kiosk::Control>& controls, ControlId id, int group = -1) {
    return test::find_control(controls, id, group);
}

class AccessGolden : public test::KioskGolden {
protected:
    void SetUp() override {
        start("body_access_golden");
        if (IsSkipped()) return;
        for (const auto& [name, cx] : {std::pair{"left", -1.2}, std::pair{"right", 1.2}}) {
            const Mesh sphere = test::uv_sphere(24, 48, Vec3(cx, 0.0, 0.0), 0.8);
            ASSERT_TRUE(
                write_obj((dir_ / (std::string(name) + ".obj")).string(), std::span<const Mesh>(&sphere, 1)).ok());
        }
    }

    // The scene with `kiosk` as its kiosk object.
    void write_scene(const std::string& kiosk) {
        std::ofstream(dir_ / "scene.json") << R"({"models": [
            {"name": "left", "file": "left.obj", "colour": [0.2, 0.5, 0.9],
             "label": {"en": {"title": "Left sphere", "description": "Tap a control to change the view."}},
             "pins": [{"anchor": [-1.2, 0.5657, 0.5657], "label": {"en": "Upper"}}]},
            {"name": "right", "file": "right.obj", "colour": [0.9, 0.5, 0.2], "label": {"en": "Right"}}],
          "camera": {"polar_deg": 90},
          "tours": [{"name": "walk", "title": {"en": "Tour"}, "steps": [{"camera": {"azimuth_deg": 30}}]}],
          "kiosk": )" << kiosk << "}";
    }

    static kiosk::UiState ui(bool large_text = false) {
        kiosk::UiState s;
        s.width = kWidth;
        s.height = kHeight;
        s.large_text = large_text;
        s.access_buttons = true;
        return s;
    }
};

// Opaque black control boxes: pixels (near) black in the control column.
size_t black(const render::Image& img, int x0, int y0, int x1, int y1) {
    size_t n = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const uint8_t* p = img.at(x, y);
            n += p[0] < 16 && p[1] < 16 && p[2] < 16;
        }
    return n;
}

TEST_F(AccessGolden, HighContrastFromTheManifestAndFromTheVisitorsToggle) {
    // The left sphere tapped: its card opens.
    const std::string select = "0.3 down 1 335 250\n0.35 up 1 335 250\n";
    write_scene(R"({"pins": true, "access_buttons": true, "high_contrast": true})");
    const render::Image manifest = play(select + "1.0 end\n");
    write_scene(R"({"pins": true, "access_buttons": true})");
    const render::Image plain = play(select + "1.0 end\n");
    std::vector<kiosk::Control> controls = kiosk::layout_controls(ui());
    kiosk::add_access_controls(ui(), controls);
    const kiosk::Control* contrast = find(controls, ControlId::Contrast);
    ASSERT_NE(contrast, nullptr);
    const render::Image toggled = play(tap_at(contrast->rect, 0.2) + select + "1.0 end\n");
    ASSERT_EQ(manifest.width, kWidth);
    // The home button's box is black in high contrast, light without.
    const kiosk::Control* home = find(controls, ControlId::Home);
    const int hx = static_cast<int>(home->rect.x) + 6, hy = static_cast<int>(home->rect.y) + 6;
    EXPECT_GT(black(manifest, hx, hy, hx + 20, hy + 10), 150u);
    EXPECT_EQ(black(plain, hx, hy, hx + 20, hy + 10), 0u);
    const auto d = test::compare(manifest, toggled);
    EXPECT_LE(d.bad_block_fraction, 0.001);
    expect_golden("access_high_contrast", manifest);
}

TEST_F(AccessGolden, LargeTextWithIcons) {
    write_scene(R"({"pins": true, "access_buttons": true, "large_text": true, "icons": true})");
    const render::Image img = play("0.3 down 1 335 250\n0.35 up 1 335 250\n1.0 end\n");
    ASSERT_EQ(img.width, kWidth);
    expect_golden("access_large_text_icons", img);
}

TEST_F(AccessGolden, TheOperatorSwitchesJapaneseOnAndTheLanguageButtonOffersIt) {
    write_scene(R"({"languages": ["en", "de"], "operator_pin": "2468"})");
    std::string replay;
    double t = 0.2;
    for (int i = 0; i < 5; ++i, t += 0.1) replay += tap_at(kiosk::Rect{4, 4, 16, 16}, t);  // the admin corner
    kiosk::UiState s = ui();
    s.access_buttons = false;
    kiosk::OperatorMode op("2468");
    op.open();
    for (int k : {2, 4, 6, 8, kiosk::OperatorMode::kOk}) {
        const kiosk::Control* key = find(op.controls(s, {}), ControlId::OperatorKey, k);
        ASSERT_NE(key, nullptr);
        replay += tap_at(key->rect, t);
        t += 0.1;
    }
    for (int k : {2, 4, 6, 8, kiosk::OperatorMode::kOk}) op.key(k);
    std::vector<std::pair<std::string, bool>> set;
    for (const std::string& l : kiosk::offered_languages({"en", "de"})) set.emplace_back(l, l == "en" || l == "de");
    ASSERT_EQ(set[9].first, "ja");
    const auto panel = op.controls(s, {}, set);
    replay += tap_at(find(panel, ControlId::OperatorLanguage, 9)->rect, t);        // ja on
    replay += tap_at(find(panel, ControlId::OperatorLanguage, 1)->rect, t + 0.1);  // de off
    replay += tap_at(find(panel, ControlId::OperatorClose)->rect, t + 0.2);
    // The language button: en -> ja.
    replay += tap_at(find(kiosk::layout_controls(s), ControlId::Language)->rect, t + 0.4);
    const render::Image img = play(replay + std::to_string(t + 1.0) + " end\n");
    ASSERT_EQ(img.width, kWidth);
    expect_golden("access_operator_japanese", img);
}

}  // namespace
}  // namespace body
