#pragma once
// Shared set-up for the golden pictures taken through bodyview (headless,
// llvmpipe, 800x500): a fresh directory for the scene, a replay played into a
// screenshot, taps placed on the kiosk's own control rectangles, and the
// comparison with tests/render/golden/ (BODY_UPDATE_GOLDENS=1 rewrites it).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "kiosk/app/ui.h"
#include "kiosk/render/image.h"

namespace body::test {

inline constexpr int kGoldenWidth = 800, kGoldenHeight = 500;

// A tap (down, up 50 ms later) in the middle of `r` at time `t`, as replay lines.
std::string tap_at(const kiosk::Rect& r, double t);
// The control `id` (and `group`, when >= 0) among `controls`, or null.
const kiosk::Control* find_control(const std::vector<kiosk::Control>& controls, kiosk::ControlId id, int group = -1);

class KioskGolden : public ::testing::Test {
protected:
    // Skips without DejaVu (fonts-dejavu-core); makes dir_ afresh.
    void start(const std::string& dir_prefix);
    void TearDown() override;
    // bodyview --headless on dir_/scene.json, playing `replay` (after a
    // `size 800 500` line); the screenshot taken at its end.
    render::Image play(const std::string& replay);
    // Within 1 % of blocks and 1.5 grey levels of mean luminance of golden/<name>.png.
    void expect_golden(const std::string& name, const render::Image& img);

    std::filesystem::path dir_;
};

}  // namespace body::test
