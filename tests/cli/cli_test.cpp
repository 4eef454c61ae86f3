#include "tests/cli/cli_test.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "body/version.h"

namespace body::test {
namespace {

TEST(Cli, VersionAndHelpExitZero) {
    for (const char* name : {"bodygen", "bodyview"}) {
        RunResult v = run(bin(name) + " --version");
        EXPECT_EQ(v.exit_code, 0) << name;
        EXPECT_EQ(v.output, std::string(name) + " " + BODY_VERSION_STRING + "\n");
        RunResult h = run(bin(name) + " --help");
        EXPECT_EQ(h.exit_code, 0) << name;
        EXPECT_NE(h.output.find("usage:"), std::string::npos) << h.output;
        EXPECT_NE(h.output.find("exit codes"), std::string::npos) << h.output;
    }
}

TEST(Cli, BadUsageExitsTwo) {
    RunResult r = run(bin("bodygen") + " frobnicate");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("unknown command 'frobnicate'"), std::string::npos);
    EXPECT_EQ(run(bin("bodygen")).exit_code, 2);
    EXPECT_EQ(run(bin("bodygen") + " check --nope x").exit_code, 2);
}

TEST(Cli, BodyviewRejectsABadTouchRotationBeforeOpeningAnything) {
    RunResult r = run(bin("bodyview") + " --headless --rotate 45 --model /nonexistent.bpm");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.output, "bodyview: --rotate: expected 0, 90, 180 or 270, got '45'\n");
}

TEST(Cli, BadContourFileIsOneLineNamingThePlace) {
    std::string path =
        std::filesystem::temp_directory_path() / ("body_cli_bad_" + std::to_string(::getpid()) + ".json");
    {
        std::ofstream(path)
            << R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": [{"points": [[0,0],[1,"x"]]}]}]})";
    }
    RunResult r = run(bin("bodygen") + " check " + path);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.output, "bodygen: " + path + ": slice 0 contour 0: point 1 must be [x, y]\n");
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace body::test

namespace body::test {
namespace {

namespace fs = std::filesystem;

TEST(CliBuild, WritesObjBpmAndOneObjPerStructureIntoADirectory) {
    const std::string stack = std::string(BODY_SOURCE_DIR) + "/tests/data/stacks/small.contours.json";
    const fs::path dir = fs::temp_directory_path() / ("body_cli_build_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);

    RunResult bpm = run(bin("bodygen") + " build " + stack + " -o " + (dir / "lobe.bpm").string() + " --quiet");
    ASSERT_EQ(bpm.exit_code, 0) << bpm.output;
    RunResult info = run(bin("bodygen") + " info " + (dir / "lobe.bpm").string());
    ASSERT_EQ(info.exit_code, 0) << info.output;
    EXPECT_NE(info.output.find("'Branching lobe'"), std::string::npos) << info.output;

    RunResult out = run(bin("bodygen") + " build " + stack + " -o " + (dir / "meshes").string() + "/ --quiet --jobs 2");
    ASSERT_EQ(out.exit_code, 0) << out.output;
    EXPECT_TRUE(fs::is_regular_file(dir / "meshes" / "lobe.obj"));
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir / "meshes")) files += entry.is_regular_file();
    EXPECT_EQ(files, 1u);  // no temporary left behind

    RunResult bad = run(bin("bodygen") + " build " + stack + " -o " + (dir / "x.obj").string() + " --jobs 0");
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_FALSE(fs::exists(dir / "x.obj"));
    fs::remove_all(dir);
}

}  // namespace
}  // namespace body::test
