#include <gtest/gtest.h>

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
}

struct BadCase {
    const char* json;
    const char* expected;  // substring of the message
};

TEST(ContourIo, BadInputNamesThePlace) {
    const BadCase cases[] = {
        {"{", "byte"},
        {R"({"format": "x", "version": 1, "slices": []})", "format"},
        {R"({"format": "bodygen.contours", "version": 2, "slices": []})", "version"},
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

}  // namespace
}  // namespace body
