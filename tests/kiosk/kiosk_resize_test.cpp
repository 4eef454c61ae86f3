// The kiosk loop follows a surface that changes size while running (the DRM
// surface after a monitor with another resolution is plugged in,
// platform/drm_display.h): from the frame the surface reports the new size,
// the app's camera has it too.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
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

// A headless surface that reports `later` as its size from the `at`-th
// poll_events() on, as the DRM surface does when a hotplug resized it there.
class ResizingSurface final : public platform::Surface {
public:
    ResizingSurface(std::unique_ptr<platform::Surface> inner, int at, int later_w, int later_h)
        : inner_(std::move(inner)), at_(at), later_w_(later_w), later_h_(later_h) {}
    platform::Backend backend() const override { return inner_->backend(); }
    void make_current() override { inner_->make_current(); }
    Status present() override { return inner_->present(); }
    int width() const override { return polls_ > at_ ? later_w_ : inner_->width(); }
    int height() const override { return polls_ > at_ ? later_h_ : inner_->height(); }
    unsigned framebuffer() const override { return inner_->framebuffer(); }
    bool poll_events(std::vector<platform::InputEvent>& out) override {
        ++polls_;
        return inner_->poll_events(out);
    }
    double time() const override { return inner_->time(); }

private:
    std::unique_ptr<platform::Surface> inner_;
    int at_, later_w_, later_h_;
    int polls_ = 0;
};

TEST(KioskResize, TheCameraFollowsTheSurfaceSize) {
    const fs::path dir = test::fresh_test_dir("body_kiosk_resize");
    const Mesh m = test::uv_sphere(8, 16, Vec3(0.0, 0.0, 0.0), 0.8);
    ASSERT_TRUE(write_obj((dir / "s.obj").string(), std::span<const Mesh>(&m, 1)).ok());
    const auto r =
        test::run(test::bin("bodygen") + " lod " + (dir / "s.obj").string() + " -o " + (dir / "s.bpm").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    std::ofstream(dir / "scene.json") << R"({"models": [{"name": "s", "file": "s.bpm"}]})";
    auto scene = scene::read_scene((dir / "scene.json").string());
    ASSERT_TRUE(scene) << scene.error().message;
    auto headless = body::test::headless_surface();
    if (!headless) GTEST_SKIP() << "no headless GL: " << headless.error().message;
    ResizingSurface surface(std::move(headless).value(), 5, 200, 160);

    KioskRunOptions o;
    o.frames = 10;
    std::vector<std::pair<int, int>> sizes;
    o.hooks.frame_done = [&](const FrameReport& f) {
        sizes.emplace_back(f.app->camera().width(), f.app->camera().height());
        return true;
    };
    EXPECT_EQ(run_kiosk(surface, scene.value(), o), 0);
    fs::remove_all(dir);
    ASSERT_EQ(sizes.size(), 10u);
    for (size_t i = 0; i < sizes.size(); ++i) {
        const auto want = i < 5 ? std::pair{320, 200} : std::pair{200, 160};
        EXPECT_EQ(sizes[i], want) << "frame " << i;
    }
}

}  // namespace
}  // namespace body::kiosk
