// `bodygen build` on bad contour files, one case per error of issue 3's list:
// each exits 2 with one line naming the file, the place (slice, contour,
// point, byte) and the reason, and leaves no output behind. Duplicate
// consecutive points are the exception: removed with a warning, and the build
// goes on.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// `stack` (a JSON object) with a "links" member.
std::string with_links(const std::string& stack, const std::string& links) {
    return stack.substr(0, stack.rfind('}')) + R"(, "links": )" + links + "}";
}
const std::string kFar = R"({"points": [[20,0],[30,0],[30,10],[20,10]]})";

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
    const std::string three_slices = kHead + R"("slices": [{"z": 0, "contours": [)" + kSquare +
                                     R"(]}, {"z": 2, "contours": [)" + kSquare + R"(]}, {"z": 4, "contours": [)" +
                                     kSquare + "]}]}";
    const BadCase cases[] = {
        // validation (builder/contours/validate.cpp)
        {"few_points", stack_with(R"({"points": [[0,0],[1,1],[0,0]]})"),
         "slice 1 contour 0: fewer than 3 distinct points"},
        {"zero_area", stack_with(R"({"points": [[0,0],[1,1],[2,2],[3,3]]})"), "slice 1 contour 0: zero area"},
        {"long_spike", stack_with(R"({"points": [[0,0],[4,0],[4,4],[2,4],[2,9],[2,4],[0,4]]})"),
         "slice 1 contour 0: zero-width spike at (2, 9); repairing it would move points by 5 (more than the repair "
         "tolerance 0.0141)"},
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
        {"wrong_version", R"({"format": "bodygen.contours", "version": 3, "slices": []})",
         "unsupported version (expected 1 or 2)"},
        // correspondence overrides (builder/contours/contour_links.cpp)
        {"links_unknown_contour", with_links(stack_with(kSquare), R"([{"cut": [[0, 0], [1, 5]]}])"),
         "links entry 0: slice 1 contour 5: no such contour"},
        {"links_unknown_slice", with_links(stack_with(kSquare), R"([{"exclude": [0, 0]}, {"join": [[7, 0], [1, 0]]}])"),
         "links entry 1: slice 7 contour 0: no such contour"},
        {"links_same_slice", with_links(stack_with(kSquare + ", " + kFar), R"([{"join": [[1, 0], [1, 1]]}])"),
         "links entry 0: slice 1 contour 0 and slice 1 contour 1 are not on adjacent slices (z = 2 and 2)"},
        {"links_not_adjacent", with_links(three_slices, R"([{"cut": [[0, 0], [2, 0]]}])"),
         "links entry 0: slice 0 contour 0 and slice 2 contour 0 are not on adjacent slices (z = 0 and 4)"},
        {"links_shape", with_links(stack_with(kSquare), R"([{"cut": [0, 1]}])"),
         R"(links entry 0: must be {"cut": [A, B]}, {"join": [A, B]} or {"exclude": A} with A, B = [slice, contour])"},
        {"links_two_edits", with_links(stack_with(kSquare), R"([{"cut": [[0, 0], [1, 0]], "exclude": [0, 0]}])"),
         R"(links entry 0: must be {"cut": [A, B]}, {"join": [A, B]} or {"exclude": A} with A, B = [slice, contour])"},
        {"links_not_array", with_links(stack_with(kSquare), "3"), R"("links" must be an array)"},
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
        // `bodygen check` reads and validates as build does: the same message for every error.
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
    EXPECT_NE(r.output.find(
                  "bodygen: warning: " + in +
                  ": slice 1 contour 0: at (1, 1): removed 3 duplicate consecutive point(s), points moved up to 0\n"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(out));
    RunResult quiet = run(bin("bodygen") + " build " + in + " -o " + out + " --quiet");
    EXPECT_EQ(quiet.exit_code, 0);
    EXPECT_EQ(quiet.output, "");
}

// Lines of `output` that start with `prefix`, in order.
std::vector<std::string> lines_with(const std::string& output, const std::string& prefix) {
    std::vector<std::string> out;
    size_t pos = 0;
    while (pos < output.size()) {
        size_t end = output.find('\n', pos);
        if (end == std::string::npos) end = output.size();
        const std::string line = output.substr(pos, end - pos);
        if (line.rfind(prefix, 0) == 0) out.push_back(line);
        pos = end + 1;
    }
    return out;
}

TEST_F(ContourCli, StrictRefusesSelfIntersectionsAndCrossingsAsBefore) {
    const std::string bow = write("bow.contours.json", stack_with(R"({"points": [[0,0],[4,4],[4,0],[0,4]]})"));
    const std::string cross =
        write("cross.contours.json",
              stack_with(R"({"points": [[0,0],[4,0],[4,4],[0,4]]}, {"points": [[2,1],[6,1],[6,3],[2,3]]})"));
    const std::pair<std::string, std::string> cases[] = {
        {bow, "slice 1 contour 0: self-intersects at (2, 2)"},
        {cross, "slice 1 contour 0: crosses slice 1 contour 1 at (4, 1)"}};
    for (const auto& [in, expected] : cases) {
        for (const char* cmd : {" build ", " check "}) {
            const std::string out = (dir / "strict.obj").string();
            RunResult r = run(bin("bodygen") + cmd + in + " --strict" + (cmd[1] == 'b' ? " -o " + out : ""));
            EXPECT_EQ(r.exit_code, 2) << r.output;
            EXPECT_EQ(r.output, "bodygen: " + in + ": " + expected + "\n");
            EXPECT_FALSE(fs::exists(out));
        }
    }
}

TEST_F(ContourCli, CheckPrintsExactlyTheRepairsBuildMakes) {
    // A bow tie, two overlapping squares, a zig-zag twist and a short spike, on three slices.
    const std::string in = write("repairs.contours.json", kHead + R"("slices": [
      {"z": 0, "contours": [{"points": [[0,0],[8,8],[8,0],[0,8]]}]},
      {"z": 2, "contours": [{"points": [[0,0],[6,0],[6,6],[0,6]]}, {"points": [[3,3],[9,3],[9,9],[3,9]]}]},
      {"z": 4, "contours": [{"points": [[0,0],[4,0],[4,0.6],[3.995,0.4],[4.005,0.4],[4,1],[4,8],[2,8],[2,8.01],[2,8],[0,8]]}]}]})");
    const std::string out = (dir / "repairs.obj").string();
    RunResult build = run(bin("bodygen") + " build " + in + " -o " + out + " --json");
    ASSERT_EQ(build.exit_code, 0) << build.output;
    RunResult check = run(bin("bodygen") + " check " + in + " --json");
    ASSERT_EQ(check.exit_code, 0) << check.output;
    const auto repairs = lines_with(build.output, "bodygen: warning: ");
    EXPECT_EQ(repairs, lines_with(check.output, "bodygen: warning: "));
    ASSERT_EQ(repairs.size(), 6u) << build.output;
    EXPECT_EQ(repairs[0], "bodygen: warning: " + in +
                              ": slice 0 contour 0: at (4, 4): self-intersection repaired into 2 contour(s), points "
                              "moved up to 0");
    // The twist at x = 4 curls into the solid (winding 2): the union keeps the region, no point moves.
    EXPECT_NE(repairs[5].find("slice 2 contour 0: at (4, 0.4): self-intersection repaired into 1 contour(s), points "
                              "moved up to 0"),
              std::string::npos)
        << repairs[5];
    EXPECT_NE(repairs[2].find("slice 1 contour 0: at (3, 6): union of 2 overlapping contours (0, 1) into 1 contour(s)"),
              std::string::npos)
        << repairs[2];
    for (const char* kind :
         {"\"self_intersection\": 2", "\"touching\": 1", "\"overlap\": 1", "\"spike\": 1", "\"collinear\": 1"}) {
        EXPECT_NE(build.output.find(kind), std::string::npos) << kind << build.output;
        EXPECT_NE(check.output.find(kind), std::string::npos) << kind << check.output;
    }
    EXPECT_NE(build.output.find("\"closed_manifold\": true"), std::string::npos);
    EXPECT_EQ(build.output.find("\"closed_manifold\": false"), std::string::npos);
    // A smaller tolerance refuses the spike, in both, with the same line.
    RunResult tight = run(bin("bodygen") + " check " + in + " --repair-tolerance 0.001");
    RunResult tight_build = run(bin("bodygen") + " build " + in + " --repair-tolerance 0.001 -o " + out + ".2.obj");
    EXPECT_EQ(tight.exit_code, 2);
    EXPECT_EQ(tight_build.exit_code, 2);
    EXPECT_EQ(lines_with(tight.output, "bodygen: "), lines_with(tight_build.output, "bodygen: "));
    EXPECT_NE(tight.output.find("slice 2 contour 0: zero-width spike at (2, 8.01); repairing it would move points by "
                                "0.01 (more than the repair tolerance 0.001)"),
              std::string::npos)
        << tight.output;
}

TEST_F(ContourCli, CheckOfManyNestedRingsIsNotQuadratic) {
    // 200 concentric rings of 64 points on 3 slices: the x-sweep compared
    // almost every pair of the 12800 edges per slice.
    std::string json = kHead + R"("slices": [)";
    for (int z = 0; z < 3; ++z) {
        json += std::string(z ? "," : "") + R"({"z": )" + std::to_string(z) + R"(, "contours": [)";
        for (int k = 0; k < 200; ++k) {
            json += std::string(k ? "," : "") + R"({"points": [)";
            for (int i = 0; i < 64; ++i) {
                const double t = 2 * 3.14159265358979 * i / 64, r = 10 + 0.5 * k;
                json += std::string(i ? "," : "") + "[" + std::to_string(r * std::cos(t)) + "," +
                        std::to_string(r * std::sin(t)) + "]";
            }
            json += "]}";
        }
        json += "]}";
    }
    const std::string in = write("rings.contours.json", json + "]}");
    RunResult r = run(bin("bodygen") + " check " + in);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("3 slices, 600 contours, 38400 points, 0 structures (units mm), 0 repair(s)"),
              std::string::npos)
        << r.output;
}

}  // namespace
}  // namespace body::test

namespace body::test {
namespace {

// `bodygen check --links` prints the correspondence build uses, with the
// file's cuts, joins and exclusions; build honours them.
TEST_F(ContourCli, CheckLinksPrintsTheCorrespondenceWithTheOverrides) {
    const std::string slices = kHead + R"("slices": [{"z": 0, "contours": [)" + kSquare + R"(]},
        {"z": 2, "contours": [)" +
                               kSquare + ", " + kFar + R"(]}, {"z": 4, "contours": [)" + kSquare + "]}]}";
    const std::string plain = write("plain.contours.json", slices);
    RunResult r = run(bin("bodygen") + " check --links " + plain);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(lines_with(r.output, "link "),
              (std::vector<std::string>{"link auto_1 [0, 0] -> [1, 0] band (computed)",
                                        "link auto_1 [1, 0] -> [2, 0] band (computed)"}));
    EXPECT_EQ(lines_with(r.output, "end auto_2 "),
              (std::vector<std::string>{"end auto_2 [1, 1] top", "end auto_2 [1, 1] bottom"}));

    const std::string edited =
        write("edited.contours.json",
              with_links(slices, R"([{"join": [[0, 0], [1, 1]]}, {"cut": [[1, 0], [2, 0]]}, {"exclude": [2, 0]}])"));
    r = run(bin("bodygen") + " check --links " + edited);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(lines_with(r.output, "link "),
              (std::vector<std::string>{"link auto_1 [0, 0] -> [1, 0] branch (computed)",
                                        "link auto_1 [0, 0] -> [1, 1] branch (joined)"}));
    EXPECT_EQ(lines_with(r.output, "excluded "), (std::vector<std::string>{"excluded [2, 0]"}));
    r = run(bin("bodygen") + " check --links --json " + edited);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(R"("origin": "joined")"), std::string::npos) << r.output;

    // Build: one structure of one piece (the join) over slices 0 and 1 only (the cut and the exclusion).
    const std::string out = (dir / "edited.obj").string();
    r = run(bin("bodygen") + " build " + edited + " -o " + out + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(R"("components": 1)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(R"("contours": 3)"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace body::test
