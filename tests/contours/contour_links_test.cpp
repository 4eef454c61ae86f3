// The "links" section of contour stack files: read, version rules, written
// back with references to the written positions, refused when wrong.
#include <gtest/gtest.h>

#include <string>

#include "builder/contours/contour_stack.h"

namespace body {
namespace {

// Three slices in the file in the order z = 4, 0, 2; two contours at z = 2.
const std::string kBody = R"("units": "mm", "slices": [
    {"z": 4, "contours": [{"points": [[0,0],[4,0],[4,4],[0,4]]}]},
    {"z": 0, "contours": [{"points": [[0,0],[4,0],[4,4],[0,4]]}]},
    {"z": 2, "contours": [{"points": [[20,0],[24,0],[24,4],[20,4]]}, {"points": [[0,0],[4,0],[4,4],[0,4]]}]}])";

std::string stack(int version, const std::string& links = "") {
    return R"({"format": "bodygen.contours", "version": )" + std::to_string(version) + ", " + kBody +
           (links.empty() ? "" : R"(, "links": )" + links) + "}";
}

// The z and first x of the contour `ref` names.
std::pair<double, double> where(const ContourStack& s, const ContourRef& ref) {
    for (const Slice& slice : s.slices)
        for (const Contour& c : slice.contours)
            if (names(ref, c)) return {slice.z, c.points[0].x};
    return {-1, -1};
}

TEST(ContourLinks, VersionOneFilesReadAsBeforeAndStayVersionOne) {
    auto s = parse_contour_stack(stack(1), "v1.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_TRUE(s->links.empty());
    ASSERT_EQ(s->slices.size(), 3u);
    EXPECT_EQ(s->slices[1].contours.size(), 2u);
    const std::string written = contour_stack_to_json(*s);
    EXPECT_NE(written.find(R"("version":1)"), std::string::npos) << written;
    EXPECT_EQ(written.find("links"), std::string::npos);
    // The same file as version 2 without links reads to the same stack.
    auto v2 = parse_contour_stack(stack(2), "v2.json");
    ASSERT_TRUE(v2.ok()) << v2.error().message;
    EXPECT_EQ(contour_stack_to_json(*v2), written);
}

TEST(ContourLinks, ReadsEditsInFileOrderWithFileIndices) {
    auto s = parse_contour_stack(stack(2, R"([{"cut": [[1, 0], [2, 1]]}, {"join": [[2, 0], [0, 0]]},
                                                {"exclude": [2, 0]}])"),
                                 "t.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    ASSERT_EQ(s->links.size(), 3u);
    EXPECT_EQ(s->links[0], (LinkOverride{LinkEdit::Cut, {1, 0}, {2, 1}}));
    EXPECT_EQ(s->links[1], (LinkOverride{LinkEdit::Join, {2, 0}, {0, 0}}));
    EXPECT_EQ(s->links[2].edit, LinkEdit::Exclude);
    EXPECT_EQ(s->links[2].a, (ContourRef{2, 0}));
    // File indices name the contours wherever sorting put them.
    EXPECT_EQ(where(*s, s->links[0].a), std::make_pair(0.0, 0.0));
    EXPECT_EQ(where(*s, s->links[0].b), std::make_pair(2.0, 0.0));
    EXPECT_EQ(where(*s, s->links[1].a), std::make_pair(2.0, 20.0));
}

TEST(ContourLinks, WritingRenumbersReferencesToTheWrittenOrder) {
    auto s = parse_contour_stack(stack(2, R"([{"cut": [[1, 0], [2, 1]]}, {"join": [[2, 0], [0, 0]]}])"), "t.json");
    ASSERT_TRUE(s.ok()) << s.error().message;
    const std::string written = contour_stack_to_json(*s);
    EXPECT_NE(written.find(R"("version":2)"), std::string::npos);
    EXPECT_NE(written.find(R"("links":[{"cut":[[0,0],[1,1]]},{"join":[[1,0],[2,0]]}])"), std::string::npos) << written;
    auto again = parse_contour_stack(written, "again.json");
    ASSERT_TRUE(again.ok()) << again.error().message;
    ASSERT_EQ(again->links.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {  // the same contours, by place
        EXPECT_EQ(where(*again, again->links[i].a), where(*s, s->links[i].a));
        EXPECT_EQ(where(*again, again->links[i].b), where(*s, s->links[i].b));
    }
    EXPECT_EQ(contour_stack_to_json(*again), written);
}

TEST(ContourLinks, BadEditsAreRefusedWithTheirEntry) {
    const std::pair<std::string, std::string> cases[] = {
        {R"([{"cut": [[1, 0], [2, 2]]}])", "t.json: links entry 0: slice 2 contour 2: no such contour"},
        {R"([{"exclude": [3, 0]}])", "t.json: links entry 0: slice 3 contour 0: no such contour"},
        {R"([{"join": [[1, 0], [0, 0]]}])",
         "t.json: links entry 0: slice 1 contour 0 and slice 0 contour 0 are not on adjacent slices (z = 0 and 4)"},
        {R"([{"cut": [[2, 0], [2, 1]]}])",
         "t.json: links entry 0: slice 2 contour 0 and slice 2 contour 1 are not on adjacent slices (z = 2 and 2)"},
        {R"([{"exclude": [0, -1]}])", "t.json: links entry 0: must be"},
        {R"([{}])", "t.json: links entry 0: must be"},
        {R"({"cut": []})", R"(t.json: "links" must be an array)"},
        {R"("none")", R"(t.json: "links" must be an array)"},
    };
    for (const auto& [links, expected] : cases) {
        SCOPED_TRACE(links);
        auto s = parse_contour_stack(stack(2, links), "t.json");
        ASSERT_FALSE(s.ok());
        EXPECT_EQ(s.error().message.rfind(expected, 0), 0u) << s.error().message;
        EXPECT_EQ(s.error().message.find('\n'), std::string::npos);
    }
}

TEST(ContourLinks, JoinsStayWithinAStructure) {
    const std::string labelled = R"({"format": "bodygen.contours", "version": 2,
      "structures": [{"id": "a"}, {"id": "b"}],
      "slices": [{"z": 0, "contours": [{"points": [[0,0],[4,0],[4,4]], "structure": "a"}]},
                 {"z": 1, "contours": [{"points": [[0,0],[4,0],[4,4]], "structure": "b"},
                                       {"points": [[9,0],[12,0],[12,4]], "structure": "a"}]}],
      "links": [{"join": [[0, 0], [1, 1]]}, {"join": [[0, 0], [1, 0]]}]})";
    auto s = parse_contour_stack(labelled, "t.json");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message, "t.json: links entry 1: join of contours of different structures ('a' and 'b')");
}

}  // namespace
}  // namespace body
