// The bodyview golden fixture (contract in kiosk_golden.h).
#include "tests/render/kiosk_golden.h"

#include <fstream>

#include "tests/cli/cli_test.h"
#include "tests/common/test_dir.h"
#include "tests/render/render_fixture.h"
#include "tests/render/render_golden.h"

namespace body::test {

namespace fs = std::filesystem;

std::string tap_at(const kiosk::Rect& r, double t) {
    const std::string at = std::to_string(r.x + r.w / 2) + " " + std::to_string(r.y + r.h / 2);
    return std::to_string(t) + " down 1 " + at + "\n" + std::to_string(t + 0.05) + " up 1 " + at + "\n";
}

const kiosk::Control* find_control(const std::vector<kiosk::Control>& controls, kiosk::ControlId id, int group) {
    for (const kiosk::Control& c : controls)
        if (c.id == id && (group < 0 || c.group == group)) return &c;
    return nullptr;
}

void KioskGolden::start(const std::string& dir_prefix) {
    if (!fs::exists("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf")) GTEST_SKIP() << "needs fonts-dejavu-core";
    dir_ = fresh_test_dir(dir_prefix);
}

void KioskGolden::TearDown() {
    if (!dir_.empty()) fs::remove_all(dir_);
}

render::Image KioskGolden::play(const std::string& replay) {
    std::ofstream(dir_ / "input.replay") << "size 800 500\n" << replay;
    auto r = run(bin("bodyview") + " --headless --size 800x500 --scene " + (dir_ / "scene.json").string() +
                 " --replay " + (dir_ / "input.replay").string() + " --screenshot " + (dir_ / "out.png").string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    auto img = render::read_png((dir_ / "out.png").string());
    EXPECT_TRUE(img) << r.output;
    return img ? img.value() : render::Image{};
}

void KioskGolden::expect_golden(const std::string& name, const render::Image& img) { test::expect_golden(name, img); }

}  // namespace body::test
