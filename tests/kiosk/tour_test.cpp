// Tours, pinned labels and the idle countdown: scene.json keys, the pure
// pieces (easing, pose interpolation, the player, the pin layout) and replays
// through KioskApp (tour start/pause/step/leave, the attract tour, pins hidden
// when occluded, a tap on a pin, the countdown and its cancelling touch).
#include "kiosk/app/tour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/label_card.h"
#include "kiosk/app/pins.h"
#include "kiosk_test_scene.h"

namespace body::kiosk {
namespace {

using test::replay;

// kTestScene's three spheres (x = -100, 0, 100, radius 40) with two tours and pins.
const char* kTourScene = R"({
  "models": [
    {"name": "left", "file": "left.obj", "group": "limbic", "label": {"en": "Left", "de": "Links"}},
    {"name": "middle", "file": "middle.obj", "group": "limbic",
     "pins": [{"anchor": [0, 0, 40], "label": {"en": {"title": "Front", "description": "The front pole"}, "de": "Vorne"}}]},
    {"name": "right", "file": "right.obj", "group": "cortex", "style": "hatching"}
  ],
  "groups": [{"name": "limbic"}, {"name": "cortex"}],
  "camera": {"azimuth_deg": 0, "polar_deg": 90},
  "tours": [
    {"name": "sides", "title": {"en": "Sides", "de": "Seiten"}, "steps": [
      {"camera": {"azimuth_deg": 90}, "caption": {"en": "From the right", "de": "Von rechts"},
       "duration": 1, "hold": 2, "easing": "linear"},
      {"visible": ["limbic"], "styles": {"middle": "lines"}, "select": "middle", "caption": {"en": "Limbic only"},
       "duration": 0.5, "hold": 2},
      {"camera": {"azimuth_deg": -90, "polar_deg": 60}, "visible": ["right", "left"], "duration": 1, "hold": 1}]},
    {"name": "spin", "steps": [{"camera": {"azimuth_deg": 180}, "duration": 2, "hold": 1},
                               {"camera": {"azimuth_deg": 0}, "duration": 2, "hold": 1}]}
  ],
  "kiosk": {"idle_seconds": 5, "reset_seconds": 10, "countdown_seconds": 4, "languages": ["en", "de"], "pins": true}
})";

KioskApp make(const std::string& text = kTourScene) {
    auto scene = scene::parse_scene(text, "tour.json", "");
    EXPECT_TRUE(scene) << scene.error().message;
    std::vector<ModelInfo> info;
    for (float x : {-100.0f, 0.0f, 100.0f}) info.push_back(ModelInfo{true, {x, 0, 0}, 40.0f, 100000, 1000});
    return KioskApp(std::move(scene).value(), std::move(info), 1280, 800);
}

const Control* find(const KioskApp& app, ControlId id, int group = -1) {
    for (const Control& c : app.controls()) {
        if (c.id == id && (group < 0 || c.group == group)) return &c;
    }
    return nullptr;
}

std::string tap(const Control* c, double t) {
    EXPECT_NE(c, nullptr);
    if (!c) return "";
    const float x = c->rect.x + c->rect.w / 2, y = c->rect.y + c->rect.h / 2;
    return std::to_string(t) + " down 5 " + std::to_string(x) + " " + std::to_string(y) + "\n" +
           std::to_string(t + 0.05) + " up 5 " + std::to_string(x) + " " + std::to_string(y) + "\n";
}

void play(KioskApp& app, double t, const std::string& text) { run_replay(app, replay(text), 60.0, t); }

// ---- scene.json ----------------------------------------------------------------

TEST(TourScene, ParsesToursPinsAndSettings) {
    auto s = scene::parse_scene(kTourScene, "tour.json", "");
    ASSERT_TRUE(s) << s.error().message;
    ASSERT_EQ(s->tours.size(), 2u);
    const scene::Tour& t = s->tours[0];
    EXPECT_EQ(t.name, "sides");
    ASSERT_EQ(t.steps.size(), 3u);
    EXPECT_EQ(*t.steps[0].camera.azimuth_deg, 90.0f);
    EXPECT_FALSE(t.steps[0].camera.polar_deg);
    EXPECT_EQ(t.steps[0].easing, scene::Easing::Linear);
    EXPECT_EQ(t.steps[1].easing, scene::Easing::EaseInOut);
    EXPECT_EQ(t.steps[1].select, "middle");
    ASSERT_TRUE(t.steps[1].visible);
    EXPECT_EQ(t.steps[1].styles.at(0).second, Style::Lines);
    EXPECT_EQ(s->text(t.steps[0].caption, "de")->title, "Von rechts");
    EXPECT_EQ(s->text(t.steps[1].caption, "de")->title, "Limbic only");  // falls back to the first language
    ASSERT_EQ(s->models[1].pins.size(), 1u);
    EXPECT_EQ(s->models[1].pins[0].anchor[2], 40.0f);
    EXPECT_TRUE(s->kiosk.pins);
    EXPECT_EQ(s->kiosk.countdown_seconds, 4.0f);
    EXPECT_EQ(s->tour_index("spin"), 1);
}

TEST(TourScene, ErrorsNameTheFileAndThePlace) {
    const std::string base =
        R"({"models": [{"name": "a", "file": "a.obj", "group": "g"}], "groups": [{"name": "g"}], )";
    const std::pair<const char*, const char*> cases[] = {
        {R"("tours": [{"name": "t", "steps": []}]})", "tour.json: tours[0].steps: expected a non-empty array"},
        {R"("tours": [{"name": "t", "steps": [{"camera": {"polar_deg": 0}}]}]})",
         "tour.json: tours[0].steps[0].camera.polar_deg: expected a number in [1, 179]"},
        {R"("tours": [{"name": "t", "steps": [{"easing": "bouncy"}]}]})",
         "tour.json: tours[0].steps[0].easing: expected linear, ease-in, ease-out or ease-in-out"},
        {R"("tours": [{"name": "t", "steps": [{"visible": ["nope"]}]}]})",
         "tour.json: tours[0].steps[0].visible[0]: no model or group named 'nope'"},
        {R"("tours": [{"name": "t", "steps": [{"select": "g"}]}]})",
         "tour.json: tours[0].steps[0].select: no model named 'g'"},
        {R"("tours": [{"name": "t", "steps": [{"caption": {"fr": "x"}}]}]})",
         "tour.json: tours[0].steps[0].caption.fr: language not listed in kiosk.languages"},
        {R"("tours": [{"name": "t", "steps": [{"zoom": 2}]}]})", "tour.json: tours[0].steps[0].zoom: unknown key"},
        {R"("tours": [{"name": "t", "steps": [{}]}, {"name": "t", "steps": [{}]}]})",
         "tour.json: tours[1].name: duplicate tour 't'"},
        {R"("kiosk": {"attract_tour": "none"}})", "tour.json: kiosk.attract_tour: no tour named 'none' in tours"},
        {R"("kiosk": {"countdown_seconds": -1}})", "tour.json: kiosk.countdown_seconds: expected a number in [0, 600]"},
        {R"("kiosk": {"pins": 1}})", "tour.json: kiosk.pins: expected true or false"},
        {R"("tours": [{"name": "t", "steps": [{"cut": {"offset": 1}}]}]})",
         "tour.json: tours[0].steps[0].cut: expected one of axis and normal"},
        {R"("tours": [{"name": "t", "steps": [{"cut": {"axis": "oblique"}}]}]})",
         "tour.json: tours[0].steps[0].cut.axis: expected axial, coronal or sagittal"},
        {R"("tours": [{"name": "t", "steps": [{"cut": {"normal": [0, 0, 0]}}]}]})",
         "tour.json: tours[0].steps[0].cut.normal: expected a non-zero normal"},
        {R"("tours": [{"name": "t", "steps": [{"cut": {"axis": "axial", "tilt": 3}}]}]})",
         "tour.json: tours[0].steps[0].cut.tilt: unknown key"},
    };
    for (const auto& [tail, message] : cases) {
        auto s = scene::parse_scene(base + tail, "tour.json", "");
        ASSERT_FALSE(s) << tail;
        EXPECT_EQ(s.error().message, message);
    }
    auto pin = scene::parse_scene(R"({"models": [{"name": "a", "file": "a.obj", "pins": [{"anchor": [0, 0]}]}]})",
                                  "tour.json", "");
    ASSERT_FALSE(pin);
    EXPECT_EQ(pin.error().message, "tour.json: models[0].pins[0].anchor: expected an array of 3 numbers");
}

// ---- easing, interpolation, player ----------------------------------------------

TEST(Tour, EasingsRunFromZeroToOneMonotonically) {
    for (scene::Easing e :
         {scene::Easing::Linear, scene::Easing::EaseIn, scene::Easing::EaseOut, scene::Easing::EaseInOut}) {
        EXPECT_FLOAT_EQ(ease(e, 0.0f), 0.0f);
        EXPECT_FLOAT_EQ(ease(e, 1.0f), 1.0f);
        EXPECT_FLOAT_EQ(ease(e, 2.0f), 1.0f);
        float last = 0.0f;
        for (int i = 1; i <= 100; ++i) {
            const float v = ease(e, static_cast<float>(i) / 100.0f);
            EXPECT_GE(v, last);
            last = v;
        }
    }
    EXPECT_LT(ease(scene::Easing::EaseIn, 0.5f), 0.5f);
    EXPECT_GT(ease(scene::Easing::EaseOut, 0.5f), 0.5f);
    EXPECT_FLOAT_EQ(ease(scene::Easing::EaseInOut, 0.5f), 0.5f);
}

TEST(Tour, PoseInterpolationTakesTheShorterWayRound) {
    CameraPose a, b;
    a.azimuth = glm::radians(170.0f);
    b.azimuth = glm::radians(-170.0f);
    a.distance = 100.0f;
    b.distance = 200.0f;
    b.target = glm::vec3(10, 0, 0);
    const CameraPose mid = interpolate_pose(a, b, 0.5f);
    EXPECT_NEAR(std::cos(mid.azimuth), -1.0f, 1e-5f);  // through 180 degrees, not through 0
    EXPECT_NEAR(mid.distance, 150.0f, 1e-4f);
    EXPECT_NEAR(mid.target.x, 5.0f, 1e-5f);
    const CameraPose end = interpolate_pose(a, b, 1.0f);
    EXPECT_NEAR(std::remainder(end.azimuth - b.azimuth, 6.2831853f), 0.0f, 1e-5f);
    // A step gives some values; the rest come from the pose before; distance 0 means home's.
    scene::TourCamera c;
    c.polar_deg = 60.0f;
    c.distance = 0.0f;
    CameraPose home;
    home.distance = 42.0f;
    const CameraPose p = step_pose(c, a, home);
    EXPECT_NEAR(p.polar, glm::radians(60.0f), 1e-6f);
    EXPECT_EQ(p.azimuth, a.azimuth);
    EXPECT_EQ(p.distance, 42.0f);
}

TEST(TourCut, NormalsTurnAlongTheGreatCircleAndPlanesSlideInAndOut) {
    const glm::vec3 z(0, 0, 1), x(1, 0, 0);
    const glm::vec3 half = turn_normal(z, x, 0.5f);
    EXPECT_NEAR(glm::length(half - glm::normalize(glm::vec3(1, 0, 1))), 0.0f, 1e-5f);
    const glm::vec3 third = turn_normal(z, x, 1.0f / 3.0f);  // 30 degrees of 90: even angles, not an even blend
    EXPECT_NEAR(std::acos(glm::dot(third, z)), 3.14159265f / 6.0f, 1e-4f);
    const glm::vec3 flip = turn_normal(z, -z, 0.5f);  // opposite: a quarter turn about some perpendicular axis
    EXPECT_NEAR(glm::length(flip), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(flip, z), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::length(turn_normal(z, -z, 1.0f) + z), 0.0f, 1e-4f);

    const TourCutPose off{}, a{true, z, -4.0f, CutAxis::Coronal}, b{true, x, 6.0f, CutAxis::Sagittal};
    const float radius = 10.0f;
    const TourCutPose mid = interpolate_cut(a, b, 0.25f, radius);
    EXPECT_TRUE(mid.on);
    EXPECT_NEAR(mid.offset, -1.5f, 1e-5f);
    EXPECT_EQ(mid.axis, CutAxis::Coronal);
    EXPECT_EQ(interpolate_cut(a, b, 0.75f, radius).axis, CutAxis::Sagittal);
    const TourCutPose in = interpolate_cut(off, a, 0.5f, radius);  // from the scene's edge toward -4
    EXPECT_TRUE(in.on);
    EXPECT_NEAR(in.offset, 3.0f, 1e-5f);
    EXPECT_NEAR(glm::length(in.normal - z), 0.0f, 1e-6f);
    EXPECT_NEAR(interpolate_cut(off, a, 0.0f, radius).offset, radius, 1e-6f);  // nothing removed yet
    const TourCutPose out = interpolate_cut(a, off, 0.5f, radius);
    EXPECT_TRUE(out.on);
    EXPECT_NEAR(out.offset, 3.0f, 1e-5f);
    EXPECT_FALSE(interpolate_cut(a, off, 1.0f, radius).on);
    EXPECT_FALSE(interpolate_cut(off, off, 0.5f, radius).on);
}

TEST(Tour, PlayerMovesHoldsAdvancesPausesAndFinishes) {
    auto s = scene::parse_scene(kTourScene, "tour.json", "");
    ASSERT_TRUE(s);
    const scene::Tour& tour = s->tours[0];  // steps: 1+2 s, 0.5+2 s, 1+1 s
    TourPlayer p;
    p.start(0, 3, false, 10.0);
    EXPECT_TRUE(p.update(10.0, tour));  // step 0 entered
    EXPECT_FALSE(p.update(10.5, tour));
    EXPECT_NEAR(p.progress(tour), 0.5f, 1e-5f);  // linear
    EXPECT_TRUE(p.update(13.0, tour));           // 1 + 2 s: step 1
    EXPECT_EQ(p.step(), 1);
    p.pause(13.2);
    EXPECT_FALSE(p.update(20.0, tour));  // the clock stands
    EXPECT_EQ(p.step(), 1);
    EXPECT_NEAR(p.elapsed(), 0.2, 1e-9);
    p.resume(20.0);
    EXPECT_TRUE(p.update(22.3, tour));  // 2.5 s of step 1 done
    EXPECT_EQ(p.step(), 2);
    EXPECT_FALSE(p.update(30.0, tour));
    EXPECT_TRUE(p.finished());
    EXPECT_EQ(p.step(), 2);
    p.previous(30.0);
    EXPECT_EQ(p.step(), 1);
    p.next(30.0);
    p.next(30.0);  // past the last step: stays there
    EXPECT_EQ(p.step(), 2);
    p.leave();
    EXPECT_FALSE(p.active());
    // A looping tour starts over after the last step.
    p.start(1, 2, true, 0.0);
    p.update(0.0, s->tours[1]);
    p.update(3.0, s->tours[1]);
    EXPECT_EQ(p.step(), 1);
    EXPECT_TRUE(p.update(6.0, s->tours[1]));
    EXPECT_EQ(p.step(), 0);
    EXPECT_FALSE(p.finished());
}

// ---- replays through the app ------------------------------------------------------

TEST(TourReplay, StartPauseStepAndLeaveFromTheControls) {
    KioskApp app = make();
    app.update(0.0);
    const float home_azimuth = app.camera().pose().azimuth;
    const Control* start = find(app, ControlId::TourStart, 0);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->text, "Sides");
    ASSERT_NE(find(app, ControlId::TourStart, 1), nullptr);
    EXPECT_EQ(find(app, ControlId::TourStart, 1)->text, "spin");  // no title: the name
    play(app, 0.0, tap(start, 0.1) + "0.65 end\n");               // started at 0.15, linear 1 s move: half way
    ASSERT_TRUE(app.tour().active());
    EXPECT_EQ(app.tour().step(), 0);
    EXPECT_NEAR(app.camera().pose().azimuth, home_azimuth + glm::radians(45.0f), 0.03f);
    EXPECT_EQ(app.tour_caption(), "From the right");
    ASSERT_NE(find(app, ControlId::TourCaption), nullptr);
    EXPECT_EQ(find(app, ControlId::TourCaption)->text, "From the right");
    EXPECT_EQ(find(app, ControlId::TourStart), nullptr);  // the row now steps the tour

    // Pause: time passes, nothing moves; play goes on.
    play(app, 0.7, tap(find(app, ControlId::TourPause), 0.7) + "3.0 end\n");
    ASSERT_TRUE(app.tour().paused());
    const float paused_at = app.camera().pose().azimuth;
    EXPECT_EQ(find(app, ControlId::TourPause)->text, "Play");
    play(app, 3.1, tap(find(app, ControlId::TourPause), 3.1) + "5.0 end\n");
    EXPECT_FALSE(app.tour().paused());
    EXPECT_NEAR(app.camera().pose().azimuth, glm::radians(90.0f), 1e-4f);
    EXPECT_NE(paused_at, app.camera().pose().azimuth);

    // Next: step 1 shows only the limbic group, selects and restyles the middle sphere.
    play(app, 5.1, tap(find(app, ControlId::TourNext), 5.1) + "5.3 end\n");
    EXPECT_EQ(app.tour().step(), 1);
    EXPECT_TRUE(app.visible(0));
    EXPECT_TRUE(app.visible(1));
    EXPECT_FALSE(app.visible(2));
    EXPECT_EQ(app.selected(), 1);
    EXPECT_EQ(app.model(1).style, Style::Lines);
    // Back returns to step 0 (all visible again).
    play(app, 5.4, tap(find(app, ControlId::TourPrevious), 5.4) + "5.6 end\n");
    EXPECT_EQ(app.tour().step(), 0);
    EXPECT_TRUE(app.visible(2));
    // A visitor's orbit pauses the tour; leave ends it and restores visibility.
    play(app, 5.7,
         tap(find(app, ControlId::TourNext), 5.7) + "6.0 down 1 300 300\n6.1 move 1 400 300\n6.2 up 1 400 300\n");
    EXPECT_TRUE(app.tour().paused());
    EXPECT_FALSE(app.visible(2));
    play(app, 6.3, tap(find(app, ControlId::TourLeave), 6.3) + "6.5 end\n");
    EXPECT_FALSE(app.tour().active());
    EXPECT_TRUE(app.visible(2));
    EXPECT_NE(find(app, ControlId::TourStart), nullptr);
}

// A tour whose steps set the cut plane (steps[].cut): a preset, a normal, then a step without one.
TEST(TourReplay, StepsSetTheCutPlaneAndLeavingTurnsItOff) {
    std::string text = kTourScene;
    const std::string spin =
        R"({"name": "spin", "steps": [{"camera": {"azimuth_deg": 180}, "duration": 2, "hold": 1},)";
    const size_t at = text.find(spin);
    ASSERT_NE(at, std::string::npos);
    text.insert(at, R"({"name": "cuts", "steps": [
        {"cut": {"axis": "coronal", "offset": -10}, "duration": 0.5, "hold": 5},
        {"cut": {"normal": [2, 0, 0], "offset": 30}, "duration": 0.5, "hold": 5},
        {"duration": 0.5, "hold": 5}]},
      )");
    auto scene = scene::parse_scene(text, "tour.json", "");
    ASSERT_TRUE(scene) << scene.error().message;
    ASSERT_TRUE(scene->tours[1].steps[0].cut);
    EXPECT_EQ(scene->tours[1].steps[0].cut->axis, 1);
    EXPECT_EQ(scene->tours[1].steps[1].cut->normal[0], 2.0f);
    EXPECT_FALSE(scene->tours[1].steps[2].cut);
    KioskApp app = make(text);
    app.update(0.0);
    // The visitor's plane before the tour.
    play(app, 0.0, tap(find(app, ControlId::Cut), 0.1) + "0.3 end\n");
    ASSERT_TRUE(app.cut().on());
    ASSERT_TRUE(app.cut().editing());
    // A tour that never sets a plane leaves it alone.
    play(app, 0.4, tap(find(app, ControlId::TourStart, 0), 0.4) + "0.6 end\n");
    EXPECT_TRUE(app.cut().on());
    play(app, 0.7, tap(find(app, ControlId::TourLeave), 0.7) + "0.9 end\n");
    EXPECT_TRUE(app.cut().on());
    // The first cut step turns the visitor's plane to its own over its 0.5 s, eased like the camera.
    const glm::vec3 visitors = app.cut().normal();
    const float visitors_offset = app.cut().offset();
    play(app, 1.0, tap(find(app, ControlId::TourStart, 1), 1.0) + "1.2 end\n");
    ASSERT_TRUE(app.tour().active());
    const float radius = app.cut().radius();
    ASSERT_GT(radius, 30.0f);  // every offset below lies inside the scene
    EXPECT_TRUE(app.cut().on());
    EXPECT_FALSE(app.cut().editing());  // fixed: gestures move the camera
    const float turned = glm::dot(app.cut().normal(), glm::vec3(0, 0, 1));
    EXPECT_GT(turned, glm::dot(visitors, glm::vec3(0, 0, 1)) + 0.01f);  // on its way from the visitor's normal
    EXPECT_LT(turned, 0.999f);                                          // not yet at coronal
    EXPECT_NE(app.cut().offset(), visitors_offset);
    play(app, 1.2, "1.3 end\n");
    EXPECT_GT(glm::dot(app.cut().normal(), glm::vec3(0, 0, 1)), turned);  // still turning
    play(app, 1.3, "1.6 end\n");
    EXPECT_NEAR(glm::length(app.cut().normal() - glm::vec3(0, 0, 1)), 0.0f, 1e-6f);  // coronal: +Z, as given
    EXPECT_NEAR(app.cut().offset(), -10.0f, 1e-5f);
    EXPECT_EQ(app.cut().axis(), CutAxis::Coronal);
    EXPECT_TRUE(app.cut().plane().enabled);
    // The next step turns the normal from +Z to +X and moves the offset from -10 to 30.
    play(app, 1.6, tap(find(app, ControlId::TourNext), 1.6) + "1.8 end\n");
    const glm::vec3 n = app.cut().normal();
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    EXPECT_GT(n.x, 0.05f);  // turning, in the plane of the two normals
    EXPECT_GT(n.z, 0.05f);
    EXPECT_NEAR(n.y, 0.0f, 1e-5f);
    EXPECT_GT(app.cut().offset(), -10.0f);
    EXPECT_LT(app.cut().offset(), 30.0f);
    play(app, 1.8, "2.2 end\n");
    EXPECT_NEAR(glm::length(app.cut().normal() - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(app.cut().offset(), 30.0f, 1e-5f);
    // A step without `cut` after one with: the plane slides out, then turns off.
    play(app, 2.2, tap(find(app, ControlId::TourNext), 2.2) + "2.4 end\n");
    EXPECT_EQ(app.tour().step(), 2);
    EXPECT_TRUE(app.cut().on());
    play(app, 2.4, "2.9 end\n");
    EXPECT_FALSE(app.cut().on());
    // Back to step 1 from no plane: it slides in along +X from the scene's edge.
    play(app, 3.0, tap(find(app, ControlId::TourPrevious), 3.0) + "3.2 end\n");
    EXPECT_TRUE(app.cut().on());
    EXPECT_NEAR(glm::length(app.cut().normal() - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_LT(app.cut().offset(), radius - 0.01f);
    EXPECT_GT(app.cut().offset(), 30.0f + 0.01f);
    play(app, 3.3, tap(find(app, ControlId::TourLeave), 3.3) + "3.5 end\n");
    EXPECT_FALSE(app.tour().active());
    EXPECT_FALSE(app.cut().on());  // leaving turns off the plane the tour set
}

TEST(TourReplay, AWatchedTourIsNotIdleAndTheAttractModePlaysItsTour) {
    std::string text = kTourScene;
    text.replace(text.find("\"pins\": true"), 12, "\"attract_tour\": \"spin\"");
    KioskApp app = make(text);
    app.update(0.0);
    // A visitor's tour playing for 7.5 s (idle_seconds 5) keeps the kiosk interactive.
    play(app, 0.0, tap(find(app, ControlId::TourStart, 0), 0.1) + "5.5 end\n");
    EXPECT_EQ(app.mode(), KioskMode::Interactive);
    EXPECT_TRUE(app.tour().active());
    play(app, 5.6, "8.0 end\n");
    EXPECT_TRUE(app.tour().finished());
    play(app, 8.1, tap(find(app, ControlId::TourLeave), 8.1) + "13.5 end\n");
    // Idle since 8.15 s: attract from 13.15 s plays the "spin" tour, looping, with no visitor controls.
    EXPECT_EQ(app.mode(), KioskMode::Attract);
    ASSERT_TRUE(app.tour().active());
    EXPECT_TRUE(app.tour().looping());
    EXPECT_EQ(app.tour().tour(), 1);
    EXPECT_EQ(find(app, ControlId::TourPause), nullptr);
    play(app, 13.6, "15.7 end\n");  // 2.55 s into the tour: step 0's move done, holding at 180 degrees
    EXPECT_NEAR(std::cos(app.camera().pose().azimuth), -1.0f, 1e-3f);
    play(app, 15.8, "20.0 end\n");  // the reset at 18.15 s does not stop it for good
    EXPECT_GE(app.resets(), 1);
    EXPECT_TRUE(app.tour().active());
    // Any touch leaves the attract tour.
    play(app, 20.1, "20.1 down 1 640 700\n20.2 up 1 640 700\n");
    EXPECT_FALSE(app.tour().active());
    EXPECT_EQ(app.mode(), KioskMode::Interactive);
}

TEST(IdleCountdown, ShowsTheLastSecondsAndATouchCancelsIt) {
    KioskApp app = make();
    play(app, 0.0, "0.0 down 1 640 700\n0.1 up 1 640 700\n");  // a visitor was here (a tap on empty space)
    play(app, 0.2, "5.5 end\n");
    EXPECT_FALSE(app.countdown());  // attract from 5.1 s, the countdown only from 6.1 s (10 - 4)
    EXPECT_EQ(find(app, ControlId::Countdown), nullptr);
    play(app, 5.6, "7.5 end\n");
    ASSERT_TRUE(app.countdown());
    EXPECT_EQ(*app.countdown(), 3);  // 10.1 - 7.5 = 2.6 s left
    const Control* box = find(app, ControlId::Countdown);
    ASSERT_NE(box, nullptr);
    EXPECT_EQ(box->text, "Still looking? 3");
    // A touch cancels it: no countdown, no reset.
    play(app, 7.6, "7.6 down 1 100 100\n7.7 up 1 100 100\n12.0 end\n");
    EXPECT_FALSE(app.countdown());
    EXPECT_EQ(app.resets(), 0);
    // Left alone it counts down to the reset, then is gone; no countdown without a visitor.
    play(app, 12.1, "17.6 end\n");
    EXPECT_EQ(*app.countdown(), 1);
    play(app, 17.7, "30.0 end\n");
    EXPECT_EQ(app.resets(), 1);
    EXPECT_FALSE(app.countdown());
    play(app, 30.1, "60.0 end\n");
    EXPECT_EQ(app.resets(), 1);
    EXPECT_FALSE(app.countdown());
}

// ---- pins -----------------------------------------------------------------------

TEST(Pins, DefaultAndGivenPinsShowAndHideWhenOccluded) {
    KioskApp app = make();
    app.update(0.0);
    ASSERT_EQ(app.pins().size(), 3u);  // left, right: default pins; middle: its given pin
    for (const PinView& p : app.pins()) {
        EXPECT_TRUE(p.shown) << p.model;
        ASSERT_TRUE(p.label) << p.model;
        // The default pin faces the start camera (+Z) at the silhouette's centre: the sphere's front pole.
        if (p.pin < 0) {
            EXPECT_NEAR(p.anchor.z, 40.0f, 0.5f) << p.model;
        }
        const glm::vec2 end = leader_end(*p.label, p.anchor_px);
        EXPECT_GT(glm::length(end - p.anchor_px), 10.0f);  // a leader line, not a label on its point
    }
    EXPECT_EQ(app.pins()[1].title, "Front");
    // Pins are controls that avoid every other control.
    size_t pin_controls = 0;
    for (const Control& c : app.controls()) {
        if (c.id != ControlId::Pin) continue;
        ++pin_controls;
        for (const Control& o : app.controls()) {
            if (&o != &c) {
                EXPECT_FALSE(rects_overlap(c.rect, o.rect)) << c.text << " / " << o.text;
            }
        }
    }
    EXPECT_EQ(pin_controls, 3u);
    // From behind (-Z) every front pole is hidden by its own sphere.
    app.camera().rotate(glm::radians(180.0f), 0.0f);
    app.update(1.0);
    for (const PinView& p : app.pins()) EXPECT_FALSE(p.shown) << p.model;
    // From above at an angle the fronts show again.
    app.camera().rotate(glm::radians(180.0f), -0.5f);
    app.update(2.0);
    for (const PinView& p : app.pins()) EXPECT_TRUE(p.shown) << p.model;
}

TEST(Pins, ASphereInFrontHidesThePinBehindIt) {
    // Two spheres on the Z axis, the camera on +Z: the back sphere's front pole is behind the front sphere.
    KioskApp app = [] {
        auto scene = scene::parse_scene(R"({"models": [
            {"name": "back", "file": "b.obj", "pins": [{"anchor": [0, 0, -60], "label": {"en": "Back"}}]},
            {"name": "front", "file": "f.obj", "pins": [{"anchor": [0, 28.28, 28.28], "label": {"en": "Upper front"}}]}],
            "kiosk": {"pins": true}})",
                                        "p.json", "");
        std::vector<ModelInfo> info{ModelInfo{true, {0, 0, -100}, 40.0f, 10, 10},
                                    ModelInfo{true, {0, 0, 0}, 40.0f, 10, 10}};
        return KioskApp(std::move(scene).value(), std::move(info), 1280, 800);
    }();
    app.update(0.0);
    ASSERT_EQ(app.pins().size(), 2u);
    EXPECT_FALSE(app.pins()[0].shown);  // (0, 0, -60) lies behind the front sphere
    EXPECT_TRUE(app.pins()[1].shown);   // the front sphere's upper front: not occluded
}

TEST(Pins, TapOnAPinOpensItsCard) {
    KioskApp app = make();
    app.update(0.0);
    const Control* pin = find(app, ControlId::Pin, 1);
    ASSERT_NE(pin, nullptr);
    play(app, 0.1, tap(pin, 0.1) + "0.3 end\n");
    EXPECT_EQ(app.selected(), 1);
    EXPECT_EQ(app.open_pin(), 1);
    const LabelCard card = label_card(app);
    EXPECT_TRUE(card.visible);
    EXPECT_EQ(card.title, "Front");
    EXPECT_EQ(card.description, "The front pole");
    // German: the pin's own text; a tap on empty space closes the card.
    app.next_language();
    app.update(0.4);
    EXPECT_EQ(app.pins()[1].title, "Vorne");
    play(app, 0.5, "0.5 down 1 640 780\n0.55 up 1 640 780\n0.7 end\n");
    EXPECT_EQ(app.open_pin(), -1);
    EXPECT_FALSE(label_card(app).visible);
}

TEST(PinLayout, NeverOverlapsAcrossRandomInputs) {
    std::mt19937 rng(27);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    size_t placed_total = 0, requested_total = 0;
    for (int round = 0; round < 500; ++round) {
        const float w = 320.0f + 1600.0f * u(rng), h = 240.0f + 900.0f * u(rng);
        const Rect screen{0, 0, w, h};
        std::vector<Rect> obstacles;
        const int n_obstacles = static_cast<int>(u(rng) * 8);
        for (int i = 0; i < n_obstacles; ++i) {
            obstacles.push_back(Rect{u(rng) * w * 0.9f, u(rng) * h * 0.9f, 40 + u(rng) * 160, 40 + u(rng) * 80});
        }
        std::vector<PinRequest> pins;
        const int n = 1 + static_cast<int>(u(rng) * 30);
        for (int i = 0; i < n; ++i) {
            pins.push_back(PinRequest{{u(rng) * w, u(rng) * h}, {40 + u(rng) * 200, 30 + u(rng) * 40}});
        }
        const float gap = 4.0f;
        const auto out = layout_pins(pins, obstacles, screen, 24.0f, gap);
        ASSERT_EQ(out.size(), pins.size());
        requested_total += pins.size();
        for (size_t i = 0; i < out.size(); ++i) {
            if (!out[i]) continue;
            ++placed_total;
            const Rect& r = *out[i];
            EXPECT_EQ(r.w, pins[i].size.x);
            EXPECT_GE(r.x, 0.0f);
            EXPECT_GE(r.y, 0.0f);
            EXPECT_LE(r.x + r.w, w);
            EXPECT_LE(r.y + r.h, h);
            for (const Rect& o : obstacles) EXPECT_FALSE(rects_overlap(r, o, gap)) << round;
            for (size_t j = 0; j < out.size(); ++j) {
                if (j != i && out[j]) {
                    EXPECT_FALSE(rects_overlap(r, *out[j], gap)) << round;
                }
                // No label covers a pin's point.
                EXPECT_FALSE(r.contains(pins[j].anchor.x, pins[j].anchor.y)) << round;
            }
            // Near its anchor: within three leader lengths.
            const glm::vec2 end = leader_end(r, pins[i].anchor);
            EXPECT_LE(glm::length(end - pins[i].anchor), 3.0f * 24.0f * 1.5f);
        }
    }
    // Crowded screens hide some labels, but most find a place.
    EXPECT_GT(placed_total, requested_total / 2);
}

TEST(PinLayout, SparsePinsAllFindAPlaceAndTheSameInputGivesTheSameLayout) {
    const Rect screen{0, 0, 1280, 800};
    const std::vector<Rect> obstacles{{1100, 0, 180, 800}};
    const std::vector<PinRequest> pins{{{300, 300}, {120, 40}}, {{600, 400}, {120, 40}}, {{1090, 100}, {150, 40}}};
    const auto a = layout_pins(pins, obstacles, screen, 24.0f, 4.0f);
    const auto b = layout_pins(pins, obstacles, screen, 24.0f, 4.0f);
    for (size_t i = 0; i < pins.size(); ++i) {
        ASSERT_TRUE(a[i]) << i;
        EXPECT_EQ(a[i]->x, b[i]->x);
        EXPECT_EQ(a[i]->y, b[i]->y);
    }
    EXPECT_LT(a[2]->x + a[2]->w, 1100.0f);  // the pin beside the column puts its label to the left
    // Up-right is the first choice.
    EXPECT_EQ(a[0]->x, 324.0f);
    EXPECT_EQ(a[0]->y, 300.0f - 24.0f - 40.0f);
}

}  // namespace
}  // namespace body::kiosk
