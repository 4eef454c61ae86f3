// The pins' occlusion by the GPU (kiosk/render/point_occlusion.h, through
// kiosk/app/pin_occlusion.h) on a headless context: a point behind an opaque
// sphere is hidden and one on its front is seen; the cut plane's removed part
// hides nothing, while its cap still does; and a KioskApp's pins follow the
// answers of the frame drawn.
#include "kiosk/render/point_occlusion.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/app/pin_occlusion.h"
#include "tests/render/render_fixture.h"

namespace body {
namespace {

// Two unit spheres on the z axis, the near one at z = 3, the far one at the
// origin; the eye at z = 10 looks down -z.
struct TwoSpheres : ::testing::Test {
    void SetUp() override {
        if (!f.ok()) GTEST_SKIP() << f.why();
        for (float z : {0.0f, 3.0f}) {
            auto id = f.renderer().add_model(sphere.data(), z > 0.0f ? "near" : "far");
            ASSERT_TRUE(id.ok());
            f.renderer().state(id.value())->transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, z));
        }
        view.eye = {0.0f, 0.0f, 10.0f};
        view.near_plane = 1.0f;
        view.far_plane = 20.0f;
        ASSERT_TRUE(queries.init().ok());
    }
    void TearDown() override {
        if (f.ok()) queries.shutdown();
    }
    // Draws the frame, then asks about `points` and waits for the answers.
    std::vector<char> hidden(const std::vector<Vec3f>& points, const render::FrameOptions& o) {
        (void)f.draw(view, render::Lighting{}, o);
        std::vector<char> out;
        EXPECT_TRUE(queries.test(view, o, points));
        EXPECT_TRUE(queries.collect(true, out));
        return out;
    }
    test::RenderFixture f{320, 200};
    test::GenMesh sphere = test::icosphere(4);
    render::View view;
    render::PointOcclusion queries;
};

TEST_F(TwoSpheres, BehindIsHiddenInFrontIsSeen) {
    // The near sphere's front pole, the far one's front pole (behind the near
    // sphere), a point beside both (seen), the far one's back pole (behind
    // itself) and a point outside the view.
    const std::vector<Vec3f> points{{0, 0, 4}, {0, 0, 1}, {2.5f, 0, 1}, {0, 0, -1}, {40, 0, 0}};
    EXPECT_EQ(hidden(points, f.frame()), (std::vector<char>{0, 1, 0, 1, 1}));
    // A point off the front pole, on the sphere's surface, is not hidden by its own surface.
    const glm::vec3 side = glm::normalize(glm::vec3(0.3f, 0.2f, 1.0f));
    EXPECT_EQ(hidden({Vec3f(side + glm::vec3(0, 0, 3))}, f.frame()), std::vector<char>{0});
}

TEST_F(TwoSpheres, TheCutPlanesRemovedPartHidesNothing) {
    render::FrameOptions o = f.frame();
    o.cut.enabled = true;
    // z > 1.5 removed: the near sphere is gone, the far one's front pole is seen.
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, -1.5f);
    EXPECT_EQ(hidden({{0, 0, 1}, {0, 0, -1}}, o), (std::vector<char>{0, 1}));
    // z > 3.5 removed: the near sphere is cut and its cap (a solid section)
    // still hides the far pole; the near one's front pole, in the removed half
    // before the cap, is seen (it is depth-tested, not clipped, as its label is drawn).
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, -3.5f);
    EXPECT_EQ(hidden({{0, 0, 1}, {0, 0, 4}}, o), (std::vector<char>{1, 0}));
}

TEST_F(TwoSpheres, NoSecondBatchWhileOneIsInFlight) {
    (void)f.draw(view);
    const std::vector<Vec3f> points{{0, 0, 4}};
    ASSERT_TRUE(queries.test(view, f.frame(), points));
    EXPECT_FALSE(queries.test(view, f.frame(), points));
    std::vector<char> out;
    ASSERT_TRUE(queries.collect(true, out));
    EXPECT_FALSE(queries.collect(true, out));  // nothing in flight any more
    EXPECT_TRUE(queries.test(view, f.frame(), points));
}

// Through the kiosk's glue: the app's pins (the manifest's anchors) are shown
// or hidden by the answers of the frame it drew; before any answer they are hidden.
TEST_F(TwoSpheres, AKioskAppsPinsFollowTheAnswers) {
    queries.shutdown();
    auto scene = scene::parse_scene(R"({"models": [
        {"name": "far", "file": "far.obj", "pins": [{"anchor": [0, 0, 1], "label": {"en": "Far"}},
                                                    {"anchor": [0, 0, -1], "label": {"en": "Back"}}]},
        {"name": "near", "file": "near.obj", "transform": {"translate": [0, 0, 3]},
         "pins": [{"anchor": [0, 0, 1], "label": {"en": "Near"}}]}],
        "camera": {"target": [0, 0, 0], "distance": 10, "azimuth_deg": 0, "polar_deg": 90},
        "kiosk": {"pins": true}})",
                                    "p.json", "");
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    const std::vector<kiosk::ModelInfo> info{{true, Vec3f(0, 0, 0), 1.0f, 10, 10},
                                             {true, Vec3f(0, 0, 3), 1.0f, 10, 10}};
    kiosk::KioskApp app(scene.value(), info, 320, 200);
    kiosk::PinOcclusion occlusion;
    ASSERT_TRUE(occlusion.init(app));
    app.update(0.0);
    ASSERT_EQ(app.pins().size(), 3u);
    for (const kiosk::PinView& p : app.pins()) EXPECT_FALSE(p.shown);  // no answer yet
    const render::View v = app.camera().render_view(glm::vec2(0.0f), Vec3f(0, 0, 1.5f), 2.5f);
    (void)f.draw(v);
    occlusion.after_render(app, v, f.frame(), true);
    EXPECT_FALSE(app.pins()[0].shown);  // the far sphere's front pole, behind the near sphere
    EXPECT_FALSE(app.pins()[1].shown);  // its back pole, behind itself
    EXPECT_TRUE(app.pins()[2].shown);   // the near sphere's front pole
    occlusion.shutdown();
}

}  // namespace
}  // namespace body
