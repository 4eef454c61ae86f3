// The body-scale scene's CI smoke run: scripts/build-body-scene.sh makes a
// scene of copies of the AAL sample (here 2 copies, 232 models where every region builds; the benchmark's
// bench/body_scene.sh uses 18, 2,088 models, which take minutes to build and
// run on llvmpipe), and the kiosk loads every model of it and draws frames.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <string>

#include "tests/cli/cli_test.h"

namespace body::test {
namespace {

TEST(BodyScene, TheScriptBuildsAManyModelSceneTheKioskLoadsWhole) {
    if (!std::filesystem::exists("/usr/share/mricron/templates/aal.nii.gz"))
        GTEST_SKIP() << "mricron-data (the AAL atlas) is not installed";
    // Per process: builds in several checkouts on one machine must not share it.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("body_scene_smoke-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    const RunResult built = run("COPIES=2 " + std::string(BODY_SOURCE_DIR) + "/scripts/build-body-scene.sh " +
                                bin("bodygen") + " " + dir.string());
    ASSERT_EQ(built.exit_code, 0) << built.output;
    std::smatch made;
    ASSERT_TRUE(std::regex_search(built.output, made, std::regex("build-body-scene: ([0-9]+) models"))) << built.output;
    const int models = std::stoi(made[1]);
    EXPECT_GE(models, 200) << "2 copies of the 116 AAL regions, less any the pipeline rejects";
    const RunResult shown = run(bin("bodyview") + " --headless --size 320x200 --scene " +
                                (dir / "scene.json").string() + " --frames 3 --kiosk-stats");
    EXPECT_EQ(shown.exit_code, 0) << shown.output;
    const std::string all = std::to_string(models);
    EXPECT_NE(shown.output.find(", " + all + "/" + all + " models,"), std::string::npos) << shown.output;
    EXPECT_EQ(shown.output.find("skipped"), std::string::npos) << shown.output;
    std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace body::test
