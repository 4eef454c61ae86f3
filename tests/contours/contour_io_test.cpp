#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <string>

#include "builder/contours/contour_stack.h"

namespace body {
namespace {

const char* kTwoSlices = R"({"format": "bodygen.contours", "version": 1, "units": "mm",
  "structures": [{"id": "k", "name": "Kidney", "color": [0.8, 0.3, 0.3]}],
  "slices": [
    {"z": 5.0, "contours": [{"points": [[0,0],[1,0],[1,1]], "structure": "k"}]},
    {"z": 1.0, "contours": [{"points": [[0,0],[2,0],[2,2]]}]},
    {"z": 5.0004, "contours": [{"points": [[3,3],[4,3],[4,4]]}]}
  ]})";

TEST(ContourIo, SortsMergesAndKeepsSourceIndices) {
    auto s = parse_contour_stack(kTwoSlices, "t.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_EQ(s->slices.size(), 2u);
    EXPECT_DOUBLE_EQ(s->slices[0].z, 1.0);
    EXPECT_EQ(s->slices[0].source_index, 1u);
    ASSERT_EQ(s->slices[1].contours.size(), 2u);  // 5.0 and 5.0004 merged
    EXPECT_EQ(s->slices[1].contours[0].structure, "k");
    EXPECT_EQ(s->slices[1].contours[1].source_slice, 2u);
    EXPECT_EQ(s->structures[0].name, "Kidney");
}

TEST(ContourIo, RoundTripsThroughJson) {
    auto s = parse_contour_stack(kTwoSlices, "t.json");
    ASSERT_TRUE(s.ok());
    auto again = parse_contour_stack(contour_stack_to_json(*s), "again.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    ASSERT_EQ(again->slices.size(), s->slices.size());
    EXPECT_EQ(again->slices[1].contours[1].points[2], Vec2(4, 4));
    EXPECT_FALSE(again->voxel);  // written only when the stack has one
}

// A label volume's voxel (bounds the build's rings) survives the file.
TEST(ContourIo, VoxelRoundTripsThroughJson) {
    auto s = parse_contour_stack(kTwoSlices, "t.json");
    ASSERT_TRUE(s.ok());
    s->voxel = 0.7;
    const std::string text = contour_stack_to_json(*s);
    EXPECT_NE(text.find("\"voxel\":0.7"), std::string::npos) << text;
    auto again = parse_contour_stack(text, "again.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    EXPECT_EQ(again->voxel, std::optional<double>(0.7));
}

struct BadCase {
    const char* json;
    const char* expected;  // substring of the message
};

TEST(ContourIo, BadInputNamesThePlace) {
    const BadCase cases[] = {
        {"{", "byte"},
        {R"({"format": "x", "version": 1, "slices": []})", "format"},
        {R"({"format": "bodygen.contours", "version": 3, "slices": []})", "version"},
        {R"({"format": "bodygen.contours", "version": 1, "slices": [{"contours": []}]})", "slice 0"},
        {R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": [{"points": [[0,0],[1]]}]}]})",
         "slice 0 contour 0: point 1"},
        {R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": []},
            {"z": 1, "contours": [{"points": [[0,0],[1,0],[0,1]], "structure": "nope"}]}]})",
         "slice 1 contour 0: unknown structure"},
        {R"({"format": "bodygen.contours", "version": 1, "structures": [{"id": "a", "color": [2, 0, 0]}], "slices": []})",
         "structure 0"},
        // Found by the fuzzer: a member of the wrong type and a number out of range.
        {R"({"format": [{"id": "k"}], "slices": []})", "format"},
        {R"({"format": "bodygen.contours", "version": 1, "units": 3, "slices": []})", "units"},
        {R"({"format": "bodygen.contours", "version": 1, "voxel": 0, "slices": []})", "\"voxel\" must be a positive"},
        {R"({"format": "bodygen.contours", "version": 1, "voxel": "1", "slices": []})", "\"voxel\" must be a positive"},
        {R"({"format": "bodygen.contours", "version": 1, "voxel": [1], "slices": []})", "\"voxel\" must be a positive"},
        {"5e777777777777777", "invalid JSON"},
    };
    for (const BadCase& c : cases) {
        auto s = parse_contour_stack(c.json, "bad.json");
        ASSERT_FALSE(s.ok()) << c.json;
        EXPECT_EQ(s.error().exit_code, kExitBadInput);
        EXPECT_NE(s.error().message.find("bad.json"), std::string::npos) << s.error().message;
        EXPECT_NE(s.error().message.find(c.expected), std::string::npos) << s.error().message;
    }
}

std::string stack_with_points(const std::string& third_point) {
    return R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": []},
      {"z": 1, "contours": [{"points": [[0,0],[1,0],[0,1]]}, {"points": [[5,5],[6,5],)" +
           third_point + "]}]}]}";
}

// "byte N" is nlohmann's count of bytes read: the 1-based index of the last byte
// of the offending token, or one past the end when the file stops early.
TEST(ContourIo, NumberOverflowNamesSliceContourPointAndByte) {
    for (const std::string token : {"1e999", "-1e999", "123456789e400"}) {
        const std::string text = stack_with_points("[6," + token + "]");
        auto s = parse_contour_stack(text, "big.json");
        ASSERT_FALSE(s.ok()) << token;
        EXPECT_EQ(s.error().exit_code, kExitBadInput);
        const size_t byte = text.find(token) + token.size();
        EXPECT_EQ(s.error().message, "big.json: slice 1 contour 1: point 2 is not finite (number overflow at byte " +
                                         std::to_string(byte) + ": '" + token + "')");
    }
    const std::string z = R"({"format": "bodygen.contours", "version": 1, "slices": [{"z": 0, "contours": []},
        {"contours": [], "z": 2e400}]})";
    auto s = parse_contour_stack(z, "z.json");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "z.json: slice 1: z is not finite (number overflow at byte " +
                                     std::to_string(z.find("2e400") + 5) + ": '2e400')");
    // Elsewhere (a color, an unknown member) it is invalid JSON at the enclosing place.
    const std::string color = R"({"format": "bodygen.contours", "version": 1,
        "structures": [{"id": "a"}, {"id": "b", "color": [1e999, 0, 0]}], "slices": []})";
    s = parse_contour_stack(color, "c.json");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "c.json: byte " + std::to_string(color.find("1e999") + 5) +
                                     ": invalid JSON at structure 1: number overflow parsing '1e999'");
}

TEST(ContourIo, TruncatedFileNamesTheByteAndWhereItStopped) {
    const std::string whole = stack_with_points("[6,6]");
    const std::string cut = whole.substr(0, whole.find("[6,6]") + 3);  // ...[6,
    auto s = parse_contour_stack(cut, "cut.json");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().exit_code, kExitBadInput);
    EXPECT_EQ(
        s.error().message.rfind(
            "cut.json: byte " + std::to_string(cut.size() + 1) + ": invalid JSON at slice 1 contour 1 point 2: ", 0),
        0u)
        << s.error().message;
    EXPECT_NE(s.error().message.find("unexpected end of input"), std::string::npos) << s.error().message;
    // A syntax error outranks a content error met before it.
    auto bad_point_then_cut = parse_contour_stack(stack_with_points("[6]").substr(0, whole.size() - 4), "x.json");
    ASSERT_FALSE(bad_point_then_cut.ok());
    EXPECT_NE(bad_point_then_cut.error().message.find("x.json: byte "), std::string::npos)
        << bad_point_then_cut.error().message;
}

TEST(ContourIo, MembersInAnyOrderAndUnknownMembersSkipped) {
    // Slices before structures (labels checked once the list is known), keys
    // shuffled, unknown members of every shape ignored.
    const char* text = R"({"slices": [{"contours": [{"structure": "k", "extra": {"a": [1, [2, {"b": null}]]},
                                        "points": [[0,0],[1,0],[1,1]]}], "note": "x", "z": 3}],
      "units": "cm", "generator": [true, false, {"x": 1e308}],
      "structures": [{"color": [0, 0.5, 1], "id": "k"}], "version": 1, "format": "bodygen.contours"})";
    auto s = parse_contour_stack(text, "any.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(s->units, "cm");
    ASSERT_EQ(s->structures.size(), 1u);
    EXPECT_EQ(s->structures[0].name, "k");
    EXPECT_DOUBLE_EQ(s->structures[0].color.g, 0.5);
    ASSERT_EQ(s->slices.size(), 1u);
    EXPECT_DOUBLE_EQ(s->slices[0].z, 3.0);
    ASSERT_EQ(s->slices[0].contours.size(), 1u);
    EXPECT_EQ(s->slices[0].contours[0].structure, "k");
    EXPECT_EQ(s->slices[0].contours[0].points[2], Vec2(1, 1));

    const char* late_unknown = R"({"slices": [{"z": 0, "contours": [{"points": [[0,0],[1,0],[1,1]]}]},
      {"z": 1, "contours": [{"points": [[0,0],[1,0],[1,1]], "structure": "q"}]}],
      "structures": [{"id": "k"}], "version": 1, "format": "bodygen.contours"})";
    auto u = parse_contour_stack(late_unknown, "late.json");
    ASSERT_FALSE(u.ok());
    EXPECT_EQ(u.error().message, "late.json: slice 1 contour 0: unknown structure 'q'");
}

TEST(ContourIo, ReadsTheFileItselfAndNamesAMissingOne) {
    const std::string path = ::testing::TempDir() + "contour_io_read.contours.json";
    {
        std::FILE* f = std::fopen(path.c_str(), "w");
        ASSERT_NE(f, nullptr);
        std::fputs(kTwoSlices, f);
        std::fclose(f);
    }
    auto from_file = read_contour_stack(path);
    auto from_text = parse_contour_stack(kTwoSlices, path);
    ASSERT_TRUE(from_file.ok()) << from_file.error().message;
    ASSERT_TRUE(from_text.ok());
    EXPECT_EQ(contour_stack_to_json(*from_file), contour_stack_to_json(*from_text));
    std::remove(path.c_str());
    auto missing = read_contour_stack(path);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().exit_code, kExitBadInput);
    EXPECT_NE(missing.error().message.find(path + ": no such file"), std::string::npos) << missing.error().message;
}

}  // namespace
}  // namespace body
