#pragma once
// The render tests' golden pictures, shared by the cut-plane, cut-volume and
// bodyview goldens: golden/<name>.png (BODY_GOLDEN_DIR, defined by each test
// target) within 1 % of blocks and 1.5 grey levels of mean luminance, the
// actual picture written beside the temporary files on a failure;
// BODY_UPDATE_GOLDENS=1 rewrites the golden instead. Also where a world
// point lands on the picture, and the skip without headless GL.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include "kiosk/render/image.h"
#include "kiosk/render/view.h"
#include "tests/render/render_fixture.h"

#define REQUIRE_GL(fixture) \
    if (!(fixture).ok()) GTEST_SKIP() << "no headless EGL/GLES 3 (Mesa libegl1/libgl1-mesa-dri): " << (fixture).why()

namespace body::test {

inline void expect_golden(const std::string& name, const render::Image& img) {
    const std::string path = std::string(BODY_GOLDEN_DIR) + "/" + name + ".png";
    if (std::getenv("BODY_UPDATE_GOLDENS")) {
        ASSERT_TRUE(render::write_png(path, img).ok());
        return;
    }
    auto golden = render::read_png(path);
    ASSERT_TRUE(golden.ok()) << golden.error().message << " (regenerate with BODY_UPDATE_GOLDENS=1)";
    const ImageDiff d = compare(golden.value(), img);
    if (d.bad_block_fraction > 0.01 || std::abs(d.mean_luma_delta) > 1.5) {
        const auto out =
            std::filesystem::temp_directory_path() / (name + ".actual." + std::to_string(getpid()) + ".png");
        (void)render::write_png(out.string(), img);
        ADD_FAILURE() << name << ": " << d.bad_block_fraction * 100 << "% blocks differ, mean luma delta "
                      << d.mean_luma_delta << " (actual written to " << out.string() << ")";
    }
}

// The pixel (column, row from the top) where world point `p` lands in a w x h picture of `view`.
inline std::pair<int, int> pixel_of(const render::View& view, Vec3f p, int w, int h) {
    const glm::vec4 c = view.projection(static_cast<float>(w) / static_cast<float>(h)) * view.view() * glm::vec4(p, 1);
    const float x = (c.x / c.w + 1.0f) * 0.5f * static_cast<float>(w),
                y = (c.y / c.w + 1.0f) * 0.5f * static_cast<float>(h);
    return {static_cast<int>(x), h - 1 - static_cast<int>(y)};
}

}  // namespace body::test
