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

// The glmark2 bunny along x: one plane crosses the mesh's self-intersections.
// It is moved past them, not left out, so no gap doubles (the stack once
// had 39 slices and a double gap there), and the stack builds closed in
// one piece with the interpolation.
TEST(SliceCli, BunnyAlongXKeepsEveryPlane) {
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(bunny)) GTEST_SKIP() << "needs " << bunny << " (Debian package glmark2-data)";
    const std::string out = temp("bunny_x.contours.json"), obj = temp("bunny_x.obj");
    RunResult r =
        run(bin("bodygen") + " slice " + bunny + " --planes 40 --axis x --avoid-self-intersections -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("moved 1 of 40 planes"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("left out"), std::string::npos) << r.output;
    auto stack = read_contour_stack(out);
    ASSERT_TRUE(stack.ok()) << stack.error().message;
    ASSERT_EQ(stack->slices.size(), 40u);
    const double even = (stack->slices.back().z - stack->slices.front().z) / 39;
    for (size_t s = 1; s < stack->slices.size(); ++s) {
        const double gap = stack->slices[s].z - stack->slices[s - 1].z;
        EXPECT_GT(gap, 0.1 * even) << s;
        EXPECT_LT(gap, 1.46 * even) << s;
    }
    r = run(bin("bodygen") + " build " + out + " --interpolate 3 --quiet --json -o " + obj);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\"closed_manifold\": true"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"components\": 1,"), std::string::npos) << r.output;
    std::filesystem::remove(out);
    std::filesystem::remove(obj);
}

}  // namespace
}  // namespace body::test
