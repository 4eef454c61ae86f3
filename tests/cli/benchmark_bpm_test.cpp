// `bodyview --headless --benchmark --model X.bpm` runs every table to the end:
// the pins table picks on the model's triangles after the .bpm handed its index
// array and vertex codes to the renderer (read back from its buffers; it
// crashed reading the released arrays). One pair per cell keeps it short.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "cli_test.h"
#include "shared/obj_io.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

namespace fs = std::filesystem;

TEST(BenchmarkCli, ABpmModelRunsEveryTableToTheEnd) {
    const fs::path dir = test::fresh_test_dir("body_benchmark_bpm");
    const Mesh sphere = test::uv_sphere(16, 32);
    ASSERT_TRUE(write_obj((dir / "s.obj").string(), std::span<const Mesh>(&sphere, 1)).ok());
    const auto lod =
        test::run(test::bin("bodygen") + " lod " + (dir / "s.obj").string() + " -o " + (dir / "s.bpm").string());
    ASSERT_EQ(lod.exit_code, 0) << lod.output;

    const auto r = test::run(test::bin("bodyview") + " --headless --size 320x200 --benchmark --bench-frames 1 " +
                             "--bench-seconds 0 --model " + (dir / "s.bpm").string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    // The pins table's row, at full detail: the file's triangles, pins shown.
    const size_t table = r.output.find("pins and labels");
    ASSERT_NE(table, std::string::npos) << r.output;
    const size_t header = r.output.find("triangles  median_ms", table);
    ASSERT_NE(header, std::string::npos) << r.output;
    std::istringstream row(r.output.substr(r.output.find('\n', header) + 1));
    size_t triangles = 0;
    double median_ms = 0, baseline_ms = 0, ratio = 0, mean_ratio = 0, cpu_ratio = 0, shown = 0;
    row >> triangles >> median_ms >> baseline_ms >> ratio >> mean_ratio >> cpu_ratio >> shown;
    ASSERT_FALSE(row.fail()) << r.output;
    EXPECT_EQ(triangles, sphere.triangle_count());
    EXPECT_GT(shown, 0.0);  // the picker found the anchors and saw them unoccluded
    fs::remove_all(dir);
}

}  // namespace
}  // namespace body
