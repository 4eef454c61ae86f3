// Golden pictures of tours and pinned labels through bodyview (headless,
// llvmpipe, 800x500): a tour's two steps, and pins at the home view (the back
// sphere's pin hidden behind the front sphere) and turned (it shows). Taps are
// placed with the same layout functions the kiosk uses. BODY_UPDATE_GOLDENS=1
// rewrites tests/render/golden/.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "kiosk/app/tour_controls.h"
#include "kiosk/render/image.h"
#include "shared/obj_io.h"
#include "tests/common/test_meshes.h"
#include "tests/render/kiosk_golden.h"
#include "tests/render/render_fixture.h"

namespace body {
namespace {

namespace fs = std::filesystem;
constexpr int kWidth = test::kGoldenWidth, kHeight = test::kGoldenHeight;

void write_sphere(const fs::path& path, double cx, double cz, double r) {
    const Mesh sphere = test::uv_sphere(24, 48, Vec3(cx, 0.0, cz), r);
    ASSERT_TRUE(write_obj(path.string(), std::span<const Mesh>(&sphere, 1)).ok());
}

class TourGolden : public test::KioskGolden {
protected:
    void SetUp() override {
        start("body_tour_golden");
        if (IsSkipped()) return;
        write_sphere(dir_ / "front.obj", 0.0, 0.0, 0.8);
        write_sphere(dir_ / "back.obj", 1.0, -2.5, 0.8);
        write_sphere(dir_ / "side.obj", -2.0, 0.0, 0.8);
        std::ofstream(dir_ / "scene.json") << R"({"models": [
            {"name": "front", "file": "front.obj", "colour": [0.2, 0.5, 0.9],
             "pins": [{"anchor": [0, 0.5657, 0.5657], "label": {"en": "Upper front"}}]},
            {"name": "back", "file": "back.obj", "colour": [0.3, 0.75, 0.35], "label": {"en": "Back"}},
            {"name": "side", "file": "side.obj", "colour": [0.9, 0.5, 0.2], "label": {"en": "Side"}}],
          "camera": {"polar_deg": 90},
          "tours": [{"name": "walk", "title": {"en": "Tour"}, "steps": [
            {"camera": {"azimuth_deg": 0}, "caption": {"en": "Three spheres"}, "duration": 0.5, "hold": 20},
            {"camera": {"azimuth_deg": 60, "polar_deg": 70}, "visible": ["front", "side"], "select": "front",
             "styles": {"side": "lines"}, "caption": {"en": "The back one hidden"}, "duration": 0.5, "hold": 20}]}],
          "kiosk": {"pins": true}})";
    }
    // A tap in the middle of the tour control `id` as the kiosk lays it out at 800x500.
    static std::string tap(kiosk::ControlId id, bool playing, double t) {
        kiosk::UiState ui;
        ui.width = kWidth;
        ui.height = kHeight;
        kiosk::TourUiState st;
        st.tour_titles = {"Tour"};
        st.playing = playing;
        std::vector<kiosk::Control> controls = kiosk::layout_controls(ui);
        kiosk::add_tour_controls(ui, st, controls);
        const kiosk::Control* c = test::find_control(controls, id);
        if (!c) ADD_FAILURE() << "no such control";
        return c ? test::tap_at(c->rect, t) : std::string();
    }
};

// Green pixels: the back sphere.
size_t green(const render::Image& img) {
    size_t n = 0;
    for (int y = 0; y < img.height; ++y) {
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            n += p[1] > p[0] + 40 && p[1] > p[2] + 40;
        }
    }
    return n;
}

TEST_F(TourGolden, TheTourSteps) {
    using kiosk::ControlId;
    const render::Image step1 = play(tap(ControlId::TourStart, false, 0.2) + "1.2 end\n");
    const render::Image step2 =
        play(tap(ControlId::TourStart, false, 0.2) + tap(ControlId::TourNext, true, 1.0) + "2.0 end\n");
    ASSERT_EQ(step1.width, kWidth);
    ASSERT_EQ(step2.width, kWidth);
    EXPECT_GT(green(step1), 500u);  // step 1 shows every sphere
    EXPECT_EQ(green(step2), 0u);    // step 2 hides the back one
    expect_golden("tour_step1", step1);
    expect_golden("tour_step2", step2);
}

// Pixels whose red or blue differ between two pictures, below the tour's
// controls and left of the kiosk's (where the spheres are).
size_t changed(const render::Image& a, const render::Image& b) {
    size_t n = 0;
    for (int y = 150; y < kHeight; ++y)
        for (int x = 0; x < 490; ++x)
            n += std::abs(int(a.at(x, y)[0]) - int(b.at(x, y)[0])) + std::abs(int(a.at(x, y)[2]) - int(b.at(x, y)[2])) >
                 40;
    return n;
}

// A step with a cut plane (steps[].cut): the same view without and with it;
// the cut removes the spheres' near halves and caps what is left. Three
// quarters of the way through the step's (linear) move the plane is on its way
// in from the scene's edge (kiosk/app/tour_cut.h): it has removed less than at the end.
TEST_F(TourGolden, AStepCutsThroughTheSpheres) {
    using kiosk::ControlId;
    std::ofstream(dir_ / "scene.json") << R"({"models": [
        {"name": "front", "file": "front.obj", "colour": [0.2, 0.5, 0.9]},
        {"name": "back", "file": "back.obj", "colour": [0.3, 0.75, 0.35]},
        {"name": "side", "file": "side.obj", "colour": [0.9, 0.5, 0.2]}],
      "camera": {"polar_deg": 90},
      "tours": [{"name": "walk", "title": {"en": "Tour"}, "steps": [
        {"camera": {"azimuth_deg": 35, "polar_deg": 65}, "caption": {"en": "Whole"}, "duration": 0.5, "hold": 20},
        {"caption": {"en": "Cut"}, "cut": {"axis": "coronal", "offset": 1.0}, "duration": 1.0, "hold": 20,
         "easing": "linear"}]}]})";
    const std::string start = tap(ControlId::TourStart, false, 0.2);
    const render::Image whole = play(start + "1.2 end\n");
    const render::Image mid = play(start + tap(ControlId::TourNext, true, 1.0) + "1.8 end\n");
    const render::Image cut = play(start + tap(ControlId::TourNext, true, 1.0) + "2.5 end\n");
    ASSERT_EQ(whole.width, kWidth);
    ASSERT_EQ(mid.width, kWidth);
    ASSERT_EQ(cut.width, kWidth);
    EXPECT_GT(changed(whole, cut), 2000u);  // the caps and what the plane removed
    EXPECT_GT(changed(whole, mid), 500u);   // on its way ...
    EXPECT_GT(changed(mid, cut), 500u);     // ... but not there yet
    EXPECT_GT(green(cut), 500u);            // the back sphere lies behind the plane, whole
    expect_golden("tour_step_cut", cut);
    expect_golden("tour_step_cut_mid", mid);
}

TEST_F(TourGolden, PinsHideBehindTheFrontSphere) {
    const render::Image home = play("0.5 end\n");
    // Turn by dragging (the back sphere's front comes out from behind the front one).
    const render::Image turned = play(
        "0.2 down 1 300 300\n0.3 move 1 260 300\n0.4 move 1 220 300\n"
        "0.5 up 1 220 300\n1.0 end\n");
    ASSERT_EQ(home.width, kWidth);
    expect_golden("pins_home", home);
    expect_golden("pins_turned", turned);
}

}  // namespace
}  // namespace body
