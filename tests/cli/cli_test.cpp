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
