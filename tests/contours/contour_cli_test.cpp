// `bodygen build` on bad contour files, one case per error of issue 3's list:
// each exits 2 with one line naming the file, the place (slice, contour,
// point, byte) and the reason, and leaves no output behind. Duplicate
// consecutive points are the exception: removed with a warning, and the build
// goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/cli/cli_test.h"
#include "tests/common/test_dir.h"

namespace body::test {
namespace {

namespace fs = std::filesystem;

class ContourCli : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override { dir = fresh_test_dir("bodygen_contour_cli"); }
    void TearDown() override { fs::remove_all(dir); }
    std::string write(const std::string& name, const std::string& text) {
        const fs::path p = dir / name;
        std::ofstream(p, std::ios::binary) << text;
        return p.string();
    }
    bool any_output() const {
        for (const auto& entry : fs::directory_iterator(dir))
            if (!entry.path().string().ends_with(".contours.json")) return true;
        return false;
    }
};

const std::string kHead = R"({"format": "bodygen.contours", "version": 1, "units": "mm", )";
const std::string kSquare = R"({"points": [[0,0],[10,0],[10,10],[0,10]]})";

// A good first slice, then `contours` on slice 1.
std::string stack_with(const std::string& contours) {
    return kHead + R"("slices": [{"z": 0, "contours": [)" + kSquare + R"(]}, {"z": 2, "contours": [)" + contours +
           "]}]}";
}

struct BadCase {
    const char* name;
    std::string json;
    std::string expected;  // the whole message after "bodygen: <file>: "
};

std::string byte_after(const std::string& text, const std::string& token) {
    return std::to_string(text.find(token) + token.size());
}

TEST_F(ContourCli, EachBadFileExitsTwoNamesThePlaceAndWritesNothing) {
    const std::string overflow = stack_with(R"({"points": [[0,0],[4,0],[4,1e999],[0,4]]})");
    const std::string overflow_z =
        kHead + R"("slices": [{"z": 0, "contours": [)" + kSquare + R"(]}, {"z": -3e400, "contours": []}]})";
    const std::string whole = stack_with(R"({"points": [[0,0],[4,0],[4,4],[0,4]]})");
    const std::string truncated = whole.substr(0, whole.find("[4,4]") + 3);
    const BadCase cases[] = {
        // validation (builder/contours/validate.cpp)
        {"few_points", stack_with(R"({"points": [[0,0],[1,1],[0,0]]})"),
         "slice 1 contour 0: fewer than 3 distinct points"},
        {"zero_area", stack_with(R"({"points": [[0,0],[1,1],[2,2],[3,3]]})"), "slice 1 contour 0: zero area"},
        {"self_intersecting", stack_with(R"({"points": [[0,0],[4,4],[4,0],[0,4]]})"),
         "slice 1 contour 0: self-intersects at (2, 2)"},
        {"crossing", stack_with(R"({"points": [[0,0],[4,0],[4,4],[0,4]]}, {"points": [[2,1],[6,1],[6,3],[2,3]]})"),
         "slice 1 contour 0: crosses slice 1 contour 1 at (4, 1)"},
        // non-finite numbers: JSON has no NaN/inf, a number past double range is the way in
        {"overflow_point", overflow,
         "slice 1 contour 0: point 2 is not finite (number overflow at byte " + byte_after(overflow, "1e999") +
             ": '1e999')"},
        {"overflow_z", overflow_z,
         "slice 1: z is not finite (number overflow at byte " + byte_after(overflow_z, "-3e400") + ": '-3e400')"},
        // format and version
        {"wrong_format", R"({"format": "other", "version": 1, "slices": []})",
         R"(not a contour stack ("format" must be "bodygen.contours"))"},
        {"not_an_object", "[1, 2, 3]", R"(not a contour stack ("format" must be "bodygen.contours"))"},
        {"wrong_version", R"({"format": "bodygen.contours", "version": 2, "slices": []})",
         "unsupported version (expected 1)"},
        // missing fields
        {"no_slices", R"({"format": "bodygen.contours", "version": 1})", R"(needs a "slices" array)"},
        {"no_z", kHead + R"("slices": [{"z": 0, "contours": []}, {"contours": []}]})",
         R"(slice 1: needs a numeric "z")"},
        {"no_contours", kHead + R"("slices": [{"z": 0, "contours": []}, {"z": 1}]})",
         R"(slice 1: needs a "contours" array)"},
        {"no_points", stack_with(R"({"structure": "k"})"), R"(slice 1 contour 0: needs a "points" array)"},
        {"no_structure_id", kHead + R"("structures": [{"id": "a"}, {"name": "B"}], "slices": []})",
         R"(structure 1: needs a string "id")"},
        // wrong types and values
        {"point_not_pair", stack_with(R"({"points": [[0,0],[1,0],[1,"x"]]})"),
         "slice 1 contour 0: point 2 must be [x, y]"},
        {"point_three_numbers", stack_with(R"({"points": [[0,0],[1,0,0],[1,1]]})"),
         "slice 1 contour 0: point 1 must be [x, y]"},
        {"z_string", kHead + R"("slices": [{"z": "0", "contours": []}]})", R"(slice 0: needs a numeric "z")"},
        {"units_number", kHead.substr(0, kHead.find("\"units\"")) + R"("units": 3, "slices": []})",
         R"("units" must be a string)"},
        {"label_number", stack_with(R"({"points": [[0,0],[4,0],[4,4]], "structure": 7})"),
         R"(slice 1 contour 0: "structure" must be a string)"},
        {"unknown_label", stack_with(R"({"points": [[0,0],[4,0],[4,4]], "structure": "liver"})"),
         "slice 1 contour 0: unknown structure 'liver'"},
        {"color_range", kHead + R"("structures": [{"id": "a", "color": [0.5, 2, 0]}], "slices": []})",
         "structure 0: color components must lie in [0, 1]"},
        // not JSON
        {"truncated", truncated,
         "byte " + std::to_string(truncated.size() + 1) +
             ": invalid JSON at slice 1 contour 0 point 2: syntax error while parsing value - unexpected end of "
             "input; expected '[', '{', or a literal"},
    };
    for (const BadCase& c : cases) {
        SCOPED_TRACE(c.name);
        const std::string in = write(std::string(c.name) + ".contours.json", c.json);
        const std::string out = (dir / (std::string(c.name) + ".obj")).string();
        RunResult r = run(bin("bodygen") + " build " + in + " -o " + out);
        EXPECT_EQ(r.exit_code, 2) << r.output;
        EXPECT_EQ(r.output, "bodygen: " + in + ": " + c.expected + "\n");
        EXPECT_FALSE(fs::exists(out));
        EXPECT_FALSE(any_output());
        // `bodygen check` only reads the file: the same message for every reader error.
        const bool validation = c.expected.find("distinct") != std::string::npos ||
                                c.expected.find("area") != std::string::npos ||
                                c.expected.find(" at (") != std::string::npos;
        if (validation) continue;
        RunResult check = run(bin("bodygen") + " check " + in);
        EXPECT_EQ(check.exit_code, 2) << check.output;
        EXPECT_EQ(check.output, "bodygen: " + in + ": " + c.expected + "\n");
    }
}

TEST_F(ContourCli, DuplicateConsecutivePointsAreRemovedWithAWarning) {
    const std::string in =
        write("dup.contours.json", stack_with(R"({"points": [[1,1],[9,1],[9,1],[9,1],[9,9],[1,9],[1,1]]})"));
    const std::string out = (dir / "dup.obj").string();
    RunResult r = run(bin("bodygen") + " build " + in + " -o " + out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(
        r.output.find("bodygen: warning: " + in + ": slice 1 contour 0: removed 3 duplicate consecutive point(s)\n"),
        std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(out));
    RunResult quiet = run(bin("bodygen") + " build " + in + " -o " + out + " --quiet");
    EXPECT_EQ(quiet.exit_code, 0);
    EXPECT_EQ(quiet.output, "");
}

}  // namespace
}  // namespace body::test
