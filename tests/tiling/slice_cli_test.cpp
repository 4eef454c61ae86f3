// bodygen slice end to end: a closed OBJ gives a readable stack; bad usage,
// a missing file and an open mesh exit 2 with one line naming the place and
// leave no output file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "builder/contours/contour_stack.h"
#include "tests/cli/cli_test.h"

namespace body::test {
namespace {

std::string temp(const std::string& name) {
    return (std::filesystem::temp_directory_path() / ("body_slice_" + std::to_string(::getpid()) + "_" + name))
        .string();
}

// A unit cube, outward (counter-clockwise seen from outside); `open` drops its x = 1 side.
void write_cube(const std::string& path, bool open) {
    std::ofstream out(path);
    for (int k = 0; k < 8; ++k) out << "v " << (k & 1) << ' ' << ((k >> 1) & 1) << ' ' << ((k >> 2) & 1) << '\n';
    const int q[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (int f = 0; f < (open ? 5 : 6); ++f)
        out << "f " << q[f][0] << ' ' << q[f][1] << ' ' << q[f][2] << ' ' << q[f][3] << '\n';
}

TEST(SliceCli, ClosedMeshGivesAStack) {
    std::string obj = temp("cube.obj"), out = temp("cube.contours.json");
    write_cube(obj, false);
    RunResult r = run(bin("bodygen") + " slice " + obj + " --planes 4 --quiet -o " + out);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    auto stack = read_contour_stack(out);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), 4u);
    EXPECT_NEAR(stack->slices[0].z, 0.125, 1e-12);
    ASSERT_EQ(stack->slices[0].contours.size(), 1u);
    const auto& square = stack->slices[0].contours[0].points;  // the side quads are split: 8 points
    EXPECT_NEAR(signed_area2(square.data(), square.size()), 2.0, 1e-12);
    std::filesystem::remove(obj);
    std::filesystem::remove(out);
}

TEST(SliceCli, BadInputExitsTwoAndWritesNothing) {
    std::string obj = temp("open.obj"), out = temp("open.contours.json");
    write_cube(obj, true);
    RunResult r = run(bin("bodygen") + " slice " + obj + " --planes 3 -o " + out);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find(obj), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("plane 0"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_EQ(run(bin("bodygen") + " slice " + obj + " --planes 0 -o " + out).exit_code, 2);
    EXPECT_EQ(run(bin("bodygen") + " slice " + obj + " --planes 3 --axis w -o " + out).exit_code, 2);
    EXPECT_EQ(run(bin("bodygen") + " slice " + obj + " --planes 3").exit_code, 2);
    EXPECT_EQ(run(bin("bodygen") + " slice " + temp("missing.obj") + " --planes 3 -o " + out).exit_code, 2);
    EXPECT_FALSE(std::filesystem::exists(out));
    std::filesystem::remove(obj);
}

}  // namespace
}  // namespace body::test
