// A six-minute soak through bodyview (headless, llvmpipe): randomised visitors
// drive the kiosk loop; every minute is logged, attract and reset happen, and
// the soak's goals (no GL error, no growth, no leaked descriptor or thread) hold.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "../cli/cli_test.h"
#include "shared/obj_io.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

namespace fs = std::filesystem;

long count_of(const std::string& text, const std::string& what) {
    long n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The soak's summary line: sessions, actions, attract entries, resets (-1 each when absent).
std::array<long, 4> summary(const std::string& output) {
    std::array<long, 4> n{-1, -1, -1, -1};
    const size_t at = output.find("bodyview: soak: ");
    if (at != std::string::npos)
        std::sscanf(output.c_str() + at, "bodyview: soak: %ld sessions, %ld actions, %ld attract entries, %ld resets",
                    &n[0], &n[1], &n[2], &n[3]);
    return n;
}

// Six minutes: the verdict judges growth after a warm-up of half the run, and the
// first visitor to reach a feature (a card's glyphs, the cut plane, a style's
// shader variants) allocates once, which the RSS at rest shows in full.
TEST(KioskSoak, SixMinutesOfVisitorsKeepEveryGoal) {
    const fs::path dir = test::fresh_test_dir("body_kiosk_soak");
    for (const char* name : {"s0.obj", "s1.obj", "s2.obj"}) {
        const double x = 2.0 * (name[1] - '1');
        const Mesh m = test::uv_sphere(16, 32, Vec3(x, 0.0, 0.0), 0.8);
        ASSERT_TRUE(write_obj((dir / name).string(), std::span<const Mesh>(&m, 1)).ok());
    }
    std::ofstream(dir / "scene.json") << R"({"models": [
        {"name": "a", "file": "s0.obj", "group": "left", "label": {"en": "Alpha"}},
        {"name": "b", "file": "s1.obj", "group": "left", "style": "hatching", "label": {"en": "Beta"}},
        {"name": "c", "file": "s2.obj", "group": "right", "label": {"en": "Gamma"}}],
        "groups": [{"name": "left"}, {"name": "right"}]})";
    const auto r = test::run(test::bin("bodyview") + " --soak 6 --size 480x300 " + dir.string() + "/");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(count_of(r.output, "bodyview: soak minute "), 6) << r.output;
    EXPECT_EQ(count_of(r.output, "gl errors 0,"), 6) << r.output;
    EXPECT_NE(r.output.find("bodyview: soak passed"), std::string::npos) << r.output;
    // The heap was given back after a reset and the RSS sampled at that rest.
    EXPECT_LT(count_of(r.output, "rss at rest 0.00 MiB"), 6) << r.output;
    EXPECT_EQ(count_of(r.output, "rss at rest "), 6) << r.output;
    const auto n = summary(r.output);
    EXPECT_GE(n[0], 2) << r.output;  // sessions
    EXPECT_GE(n[2], 1) << r.output;  // attract entries
    EXPECT_GE(n[3], 1) << r.output;  // resets
    fs::remove_all(dir);
}

TEST(KioskSoak, BadMinutesAreAUsageError) {
    const auto r = test::run(test::bin("bodyview") + " --soak 0 --model /nonexistent.obj");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find("--soak expects MINUTES"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace body
