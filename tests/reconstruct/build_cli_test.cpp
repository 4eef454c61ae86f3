// `bodygen build` end to end: a good stack gives a closed OBJ and stats, the
// parallel build equals the serial one, bad options exit 2. Bad contour files:
// tests/contours/contour_cli_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "shared/obj_io.h"
#include "tests/cli/cli_test.h"
#include "tests/common/test_dir.h"

namespace body::test {
namespace {

namespace fs = std::filesystem;

class BuildCli : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override { dir = fresh_test_dir("bodygen_build"); }
    void TearDown() override { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir / name;
        std::ofstream(p) << text;
        return p.string();
    }
};

std::string stack_with(const std::string& second_slice_contours) {
    return R"({"format": "bodygen.contours", "version": 1, "units": "mm", "slices": [
      {"z": 0, "contours": [{"points": [[0,0],[10,0],[10,10],[0,10]]}]},
      {"z": 2, "contours": [)" +
           second_slice_contours + "]}]}";
}

TEST_F(BuildCli, BuildsClosedMeshesAndPrintsStats) {
    const std::string in = write("two.contours.json", R"({"format": "bodygen.contours", "version": 1,
      "structures": [{"id": "a", "name": "Left", "color": [1, 0, 0]}],
      "slices": [
        {"z": 0, "contours": [{"points": [[0,0],[10,0],[10,10],[0,10]], "structure": "a"},
                              {"points": [[20,0],[30,0],[30,10],[20,10]]}]},
        {"z": 1.5, "contours": [{"points": [[1,1],[9,1],[9,9],[1,9]], "structure": "a"},
                                {"points": [[21,0],[31,0],[31,10],[21,10]]}]},
        {"z": 4, "contours": [{"points": [[2,2],[8,2],[8,8],[2,8]], "structure": "a"}]}]})");
    const std::string out = (dir / "out.obj").string();
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + out + " --json --caps dome --tiling multires");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\"closed_manifold\": true"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("Left"), std::string::npos);
    EXPECT_NE(r.output.find("genus"), std::string::npos);
    auto meshes = read_obj(out);
    ASSERT_TRUE(meshes.ok()) << meshes.error().message;
    ASSERT_EQ(meshes->size(), 2u);
    for (const Mesh& m : *meshes) {
        // read_obj welds by index, so the topology check sees the written mesh.
        EXPECT_TRUE(analyze_topology(m.positions, m.indices).closed_manifold()) << m.name;
        EXPECT_GT(mesh_volume(m.positions, m.indices), 0.0);
    }
    RunResult quiet = run(bin("bodygen") + " build " + in + " -o " + out + " --quiet");
    EXPECT_EQ(quiet.exit_code, 0);
    EXPECT_EQ(quiet.output, "");
}

// Structure "a" is missing from the middle slice (a gap), "b" spans all three:
// built in parallel, "a" must still be two closed pieces capped at the gap, the
// same OBJ as the one-thread build.
TEST_F(BuildCli, ParallelBuildKeepsAGapInAStructure) {
    const std::string in = write("gap.contours.json", R"({"format": "bodygen.contours", "version": 1,
      "structures": [{"id": "a", "name": "A", "color": [1, 0, 0]}, {"id": "b", "name": "B", "color": [0, 1, 0]}],
      "slices": [
        {"z": 0, "contours": [{"points": [[0,0],[10,0],[10,10],[0,10]], "structure": "a"},
                              {"points": [[20,0],[30,0],[30,10],[20,10]], "structure": "b"}]},
        {"z": 2, "contours": [{"points": [[21,0],[31,0],[31,10],[21,10]], "structure": "b"}]},
        {"z": 4, "contours": [{"points": [[1,1],[9,1],[9,9],[1,9]], "structure": "a"},
                              {"points": [[20,1],[30,1],[30,9],[20,9]], "structure": "b"}]}]})");
    const std::string one = (dir / "one.obj").string(), two = (dir / "two.obj").string();
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + one + " --quiet --jobs 1").exit_code, 0);
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + two + " --quiet --jobs 2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto serial = read_obj(one), parallel = read_obj(two);
    ASSERT_TRUE(serial.ok() && parallel.ok());
    ASSERT_EQ(parallel->size(), 2u);
    ASSERT_EQ(serial->size(), parallel->size());
    for (size_t i = 0; i < serial->size(); ++i) {
        const Mesh &s = (*serial)[i], &p = (*parallel)[i];
        EXPECT_EQ(s.name, p.name);
        EXPECT_EQ(s.indices.size(), p.indices.size()) << s.name;
        EXPECT_NEAR(mesh_volume(s.positions, s.indices), mesh_volume(p.positions, p.indices), 1e-9) << s.name;
        EXPECT_TRUE(analyze_topology(p.positions, p.indices).closed_manifold()) << p.name;
    }
    // "a" is two capped pieces (nothing bridges z 0..4), so two components.
    const Mesh& a = (*parallel)[0].name == "A" ? (*parallel)[0] : (*parallel)[1];
    EXPECT_EQ(analyze_topology(a.positions, a.indices).components, 2u);
}

// Every bad contour file (exit 2, one line naming the place, nothing written) is
// covered through `bodygen build` in tests/contours/contour_cli_test.cpp.

TEST_F(BuildCli, BadOptionsExitTwo) {
    const std::string in = write("ok.contours.json", stack_with(R"({"points": [[0,0],[10,0],[10,10],[0,10]]})"));
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + (dir / "x.obj").string() + " --caps round");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--caps must be flat|dome|none"), std::string::npos) << r.output;
    EXPECT_EQ(run(bin("bodygen") + " build " + in).exit_code, 2);  // no -o
    r = run(bin("bodygen") + " build " + in + " -o " + (dir / "x.obj").string() + " --smooth -3");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--smooth must be between 0 and 1000"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "x.obj"));
}

// --smooth moves vertices and keeps the mesh closed;
// --smooth 0 is the unsmoothed build, byte for byte.
TEST_F(BuildCli, SmoothMovesVerticesAndKeepsTheMeshClosed) {
    const std::string in = write("three.contours.json", R"({"format": "bodygen.contours", "version": 1, "slices": [
      {"z": 0, "contours": [{"points": [[0,0],[10,0],[10,10],[0,10]]}]},
      {"z": 2, "contours": [{"points": [[-2,-2],[12,-2],[12,12],[-2,12]]}]},
      {"z": 4, "contours": [{"points": [[1,1],[9,1],[9,9],[1,9]]}]}]})");
    const std::string raw = (dir / "raw.obj").string(), zero = (dir / "zero.obj").string(),
                      smooth = (dir / "smooth.obj").string();
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + raw + " --quiet").exit_code, 0);
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + zero + " --quiet --smooth 0").exit_code, 0);
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + smooth + " --json --smooth 5");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\"smooth\": 5"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\"closed_manifold\": true"), std::string::npos) << r.output;
    auto a = read_obj(raw), b = read_obj(zero), c = read_obj(smooth);
    ASSERT_TRUE(a.ok() && b.ok() && c.ok());
    EXPECT_EQ((*a)[0].positions, (*b)[0].positions);
    ASSERT_EQ((*a)[0].indices, (*c)[0].indices);
    size_t moved = 0;  // most vertices: only the contour corners' neighbourhoods are flat
    for (size_t v = 0; v < (*c)[0].positions.size(); ++v)
        moved += glm::length((*c)[0].positions[v] - (*a)[0].positions[v]) > 1e-3;
    EXPECT_GT(moved, (*c)[0].positions.size() / 2);
    EXPECT_TRUE(analyze_topology((*c)[0].positions, (*c)[0].indices).closed_manifold());
}

// One structure, interpolated: --jobs beyond the structures searches its
// slabs for meeting triangles on threads; the file is byte for byte the
// one-thread build's. Rings of 24 points whose radius and centre wander from
// slice to slice, so rungs curve and the search has pairs to test.
TEST_F(BuildCli, ParallelGuardGivesTheSameInterpolatedFile) {
    std::string json = R"({"format": "bodygen.contours", "version": 1, "slices": [)";
    for (int s = 0; s < 8; ++s) {
        json += std::string(s ? "," : "") + "{\"z\": " + std::to_string(s) + ", \"contours\": [{\"points\": [";
        const double r = 5.0 + 2.0 * std::sin(0.9 * s), cx = 1.5 * std::cos(0.7 * s);
        for (int i = 0; i < 24; ++i) {
            const double a = 2.0 * 3.14159265358979 * i / 24.0, ri = r * (1.0 + 0.15 * std::cos(3.0 * a + s));
            json += std::string(i ? "," : "") + "[" + std::to_string(cx + ri * std::cos(a)) + "," +
                    std::to_string(ri * std::sin(a)) + "]";
        }
        json += "]}]}";
    }
    json += "]}";
    const std::string in = write("wander.contours.json", json);
    const std::string one = (dir / "one.obj").string(), three = (dir / "three.obj").string();
    const std::string linear = (dir / "linear.obj").string();
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + linear + " --quiet --interpolate 0").exit_code, 0);
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + one + " --quiet --interpolate 3 --jobs 1").exit_code, 0);
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + three + " --quiet --interpolate 3 --jobs 3");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    auto text = [](const std::string& path) {
        std::ifstream f(path, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    };
    const std::string serial = text(one);
    EXPECT_FALSE(serial.empty());
    EXPECT_EQ(serial, text(three));
    auto a = read_obj(linear), b = read_obj(one);
    ASSERT_TRUE(a.ok() && b.ok());
    EXPECT_GT((*b)[0].indices.size(), (*a)[0].indices.size());  // rings were added
}

// --interpolate N adds rings between the slices and keeps the mesh closed
// (--ring-tolerance 0: on every rung, though these squares' rungs are straight);
// --min-area drops a speck of a contour stack with the warning check prints too.
TEST_F(BuildCli, InterpolateAndMinArea) {
    const std::string in = write("speck.contours.json", R"({"format": "bodygen.contours", "version": 1, "slices": [
      {"z": 0, "contours": [{"points": [[0,0],[10,0],[10,10],[0,10]]}]},
      {"z": 2, "contours": [{"points": [[-2,-2],[12,-2],[12,12],[-2,12]]}]},
      {"z": 4, "contours": [{"points": [[1,1],[9,1],[9,9],[1,9]]}, {"points": [[20,0],[20.5,0],[20.5,0.5]]}]}]})");
    const std::string raw = (dir / "raw.obj").string(), rings = (dir / "rings.obj").string();
    // --interpolate 0: linear bands, every vertex on a slice plane or a cap.
    ASSERT_EQ(run(bin("bodygen") + " build " + in + " -o " + raw + " --interpolate 0 --quiet").exit_code, 0);
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + rings + " --json --interpolate 3 --ring-tolerance 0");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\"interpolate\": 3"), std::string::npos) << r.output;
    auto a = read_obj(raw), b = read_obj(rings);
    ASSERT_TRUE(a.ok() && b.ok());
    ASSERT_EQ(a->size(), 2u);  // the speck is a structure of its own
    EXPECT_GT((*b)[0].indices.size(), (*a)[0].indices.size());
    EXPECT_TRUE(analyze_topology((*b)[0].positions, (*b)[0].indices).closed_manifold());

    // Without the option the command line interpolates (3 rings, default
    // tolerance): a cone whose radius grows 2, 5, 7, 8 curves between its
    // slices; --interpolate 0 leaves no vertex strictly between two slices.
    std::string cone = R"({"format": "bodygen.contours", "version": 1, "slices": [)";
    for (int k = 0; k < 4; ++k) {
        const double radius[] = {2, 5, 7, 8};
        cone += std::string(k ? "," : "") + R"({"z": )" + std::to_string(k) + R"(, "contours": [{"points": [)";
        for (int i = 0; i < 16; ++i)
            cone += std::string(i ? "," : "") + "[" + std::to_string(radius[k] * std::cos(i * M_PI / 8)) + "," +
                    std::to_string(radius[k] * std::sin(i * M_PI / 8)) + "]";
        cone += "]}]}";
    }
    const std::string cone_in = write("cone.contours.json", cone + "]}");
    const auto between_slices = [](const Mesh& m) {
        size_t n = 0;
        for (const Vec3& p : m.positions) n += p.z > 0.0 && p.z < 3.0 && std::abs(p.z - std::round(p.z)) > 1e-9;
        return n;
    };
    const std::string plain = (dir / "default.obj").string();
    r = run(bin("bodygen") + " build " + cone_in + " -o " + plain + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("\"interpolate\": 3"), std::string::npos) << r.output;
    auto c = read_obj(plain);
    ASSERT_TRUE(c.ok());
    EXPECT_GT(between_slices((*c)[0]), 0u);
    EXPECT_TRUE(analyze_topology((*c)[0].positions, (*c)[0].indices).closed_manifold());
    ASSERT_EQ(run(bin("bodygen") + " build " + cone_in + " -o " + plain + " --interpolate 0 --quiet").exit_code, 0);
    c = read_obj(plain);
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(between_slices((*c)[0]), 0u);

    r = run(bin("bodygen") + " build " + in + " -o " + raw + " --min-area 0.5");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("slice 2 contour 1: at (20, 0): dropped a contour of area 0.125 (under --min-area 0.5)"),
              std::string::npos)
        << r.output;
    a = read_obj(raw);
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a->size(), 1u);
    RunResult check = run(bin("bodygen") + " check " + in + " --min-area 0.5 --json");
    EXPECT_EQ(check.exit_code, 0) << check.output;
    EXPECT_NE(check.output.find("\"small\": 1"), std::string::npos) << check.output;

    r = run(bin("bodygen") + " build " + in + " -o " + raw + " --interpolate 65");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--interpolate must be between 0 and 64"), std::string::npos) << r.output;
    r = run(bin("bodygen") + " build " + in + " -o " + raw + " --min-area -1");
    EXPECT_EQ(r.exit_code, 2);
    r = run(bin("bodygen") + " build " + in + " -o " + raw + " --interpolate 3 --ring-tolerance 1.5");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.output.find("--ring-tolerance must be between 0 and 1"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace body::test
