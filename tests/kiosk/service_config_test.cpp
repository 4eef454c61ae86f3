// The service's configuration file: keys become bodyview's options, the command
// line wins, bad lines name the file and line.
#include "kiosk/modes/service_config.h"

#include <gtest/gtest.h>

#include <fstream>

#include "kiosk/modes/view_options.h"
#include "tests/common/test_dir.h"

namespace body::kiosk {
namespace {

Result<std::vector<std::string>> apply(const std::vector<std::string>& argv) {
    return apply_config_file(argv, view_value_options(), view_flag_options());
}

class ServiceConfig : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::fresh_test_dir("body_service_config"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::string write(const std::string& text) {
        const std::string path = (dir_ / "bodyview.conf").string();
        std::ofstream(path) << text;
        return path;
    }
    std::filesystem::path dir_;
};

TEST_F(ServiceConfig, KeysBecomeOptionsAndTheCommandLineWins) {
    const std::string path = write(
        "# comment\nbundle = /srv/exhibit\nplatform = drm\nrotation = 90   # panel turned\n"
        "touch_calibration = 1 0 0 0 1 0\ndisplay_mode =\nlog_level = debug\n");
    auto args = apply({"--config", path, "--rotate", "180"});
    ASSERT_TRUE(args) << args.error().message;
    const std::vector<std::string> expected = {
        "--rotate", "180", "/srv/exhibit", "--platform=drm", "--log-level=debug", "--touch-calibration=1 0 0 0 1 0"};
    auto sorted = [](std::vector<std::string> v) {
        std::sort(v.begin(), v.end());
        return v;
    };
    EXPECT_EQ(sorted(args.value()), sorted(expected));
    // A bundle on the command line replaces the config's.
    auto own = apply({"--config=" + path, "/other/bundle"});
    ASSERT_TRUE(own);
    EXPECT_EQ(std::count(own->begin(), own->end(), "/srv/exhibit"), 0);
    // The result parses as bodyview's command line.
    auto parsed = CliArgs::parse(args.value(), view_value_options(), view_flag_options());
    ASSERT_TRUE(parsed) << parsed.error().message;
    auto o = parse_view_options(parsed.value());
    ASSERT_TRUE(o) << o.error().message;
    EXPECT_EQ(o->surface.touch_rotation, 180);
    EXPECT_EQ(o->log_level, platform::LogLevel::Debug);
    EXPECT_EQ(o->scene_path, "/srv/exhibit/scene.json");
}

TEST_F(ServiceConfig, BadLinesNameFileAndLine) {
    const std::string path = write("bundle = /x\ncolour = red\n");
    auto r = apply({"--config", path});
    ASSERT_FALSE(r);
    EXPECT_EQ(r.error().exit_code, kExitBadInput);
    EXPECT_NE(r.error().message.find(path + ":2: unknown key 'colour'"), std::string::npos) << r.error().message;
    auto no_eq = apply({"--config", write("bundle /x\n")});
    ASSERT_FALSE(no_eq);
    EXPECT_NE(no_eq.error().message.find(":1: expected 'key = value'"), std::string::npos);
    EXPECT_FALSE(apply({"--config", (dir_ / "missing.conf").string()}));
    EXPECT_FALSE(apply({"--config"}));
    auto none = apply({"a/", "--rotate", "90"});  // no --config: unchanged
    ASSERT_TRUE(none);
    EXPECT_EQ(none.value(), (std::vector<std::string>{"a/", "--rotate", "90"}));
}

TEST_F(ServiceConfig, ThePackagedFileParses) {
    auto r = apply({"--config", std::string(BODY_SOURCE_DIR) + "/packaging/bodyview.conf"});
    ASSERT_TRUE(r) << r.error().message;
    auto parsed = CliArgs::parse(r.value(), view_value_options(), view_flag_options());
    ASSERT_TRUE(parsed) << parsed.error().message;
    auto o = parse_view_options(parsed.value());
    ASSERT_TRUE(o) << o.error().message;
    EXPECT_EQ(o->scene_path, "/usr/share/bodyview/exhibit/scene.json");
}

}  // namespace
}  // namespace body::kiosk
