// Labels are shaped lazily: in a scene of 2,000 models, each with a pinned
// label, the kiosk's first frames shape the text of the labels and controls on
// screen only (Overlay::shaped_lines), not every model's label.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/kiosk_run.h"
#include "shared/obj_io.h"
#include "shared/scene/scene.h"
#include "tests/common/headless_surface.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body::kiosk {
namespace {

namespace fs = std::filesystem;

TEST(LazyLabels, TwoThousandModelsShapeOnlyTheLabelsOnScreen) {
    const fs::path dir = test::fresh_test_dir("body_lazy_labels");
    const Mesh m = test::uv_sphere(3, 6, Vec3(0.0), 1.0);
    ASSERT_TRUE(write_obj((dir / "s.obj").string(), std::span<const Mesh>(&m, 1)).ok());
    // 2,000 small spheres on a 20 x 10 x 10 grid, 40 groups, one label each.
    const int models = 2000;
    std::string json = "{\"models\": [";
    for (int i = 0; i < models; ++i) {
        json += i ? ",{" : "{";
        json += "\"name\": \"m" + std::to_string(i) + "\", \"file\": \"s.obj\", \"group\": \"g";
        json += std::to_string(i % 40) + "\", \"transform\": {\"translate\": [";
        json += std::to_string(i % 20 * 3) + ", " + std::to_string(i / 20 % 10 * 3) + ", ";
        json += std::to_string(i / 200 * 3) + "]}, \"label\": {\"en\": \"Structure number ";
        json += std::to_string(i) + "\"}}";
    }
    json += "], \"groups\": [";
    for (int g = 0; g < 40; ++g) json += (g ? ",{\"name\": \"g" : "{\"name\": \"g") + std::to_string(g) + "\"}";
    json += "], \"kiosk\": {\"pins\": true, \"languages\": [\"en\"]}}";
    std::ofstream(dir / "scene.json") << json;
    auto scene = scene::read_scene((dir / "scene.json").string());
    ASSERT_TRUE(scene) << scene.error().message;
    auto surface = body::test::headless_surface(640, 400);
    if (!surface) GTEST_SKIP() << "no headless GL: " << surface.error().message;

    KioskRunOptions o;
    o.frames = 3;
    size_t shaped = 0, controls = 0, pins_shown = 0, pins_labelled = 0;
    o.hooks.frame_done = [&](const FrameReport& f) {
        shaped = f.shaped_lines;
        controls = f.app->controls().size();
        pins_shown = pins_labelled = 0;
        for (const PinView& p : f.app->pins()) pins_shown += p.shown, pins_labelled += p.label.has_value();
        return true;
    };
    EXPECT_EQ(run_kiosk(*surface.value(), scene.value(), o), 0);
    fs::remove_all(dir);
    // Every model has a pin; many are on screen, a few have room for their label.
    EXPECT_GT(pins_shown, 100u);
    EXPECT_GT(pins_labelled, 0u);
    EXPECT_LT(pins_labelled, pins_shown);
    // Shaped: the texts of the controls drawn (labels among them), a few lines
    // each as the fitting rule tries its wraps; never the labels left off.
    EXPECT_GT(shaped, 0u);
    EXPECT_LE(shaped, 4 * controls);
    EXPECT_LT(shaped, pins_shown);
}

}  // namespace
}  // namespace body::kiosk
