// The edge mesh of the `lines` style.
#include "kiosk/render/edge_list.h"

#include <gtest/gtest.h>

#include <set>

using namespace body::render;

TEST(EdgeList, ClosedCubeHasEighteenPairedEdges) {
    std::vector<uint32_t> idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    auto edges = build_edge_list(idx);
    ASSERT_EQ(edges.size(), 18u);
    std::set<std::pair<uint32_t, uint32_t>> seen;
    for (const auto& e : edges) {
        EXPECT_NE(e.b, kNoVertex);
        EXPECT_TRUE(seen.insert({std::min(e.v0, e.v1), std::max(e.v0, e.v1)}).second);
        // (v0, v1, a) is a face of the input with that orientation.
        bool found = false;
        for (size_t f = 0; f < idx.size(); f += 3)
            for (int k = 0; k < 3; ++k)
                found |= idx[f + k] == e.v0 && idx[f + (k + 1) % 3] == e.v1 && idx[f + (k + 2) % 3] == e.a;
        EXPECT_TRUE(found);
    }
}

TEST(EdgeList, OpenMeshHasBoundaries) {
    std::vector<uint32_t> quad = {0, 1, 2, 0, 2, 3};
    auto edges = build_edge_list(quad);
    ASSERT_EQ(edges.size(), 5u);
    int boundary = 0;
    for (const auto& e : edges) boundary += e.b == kNoVertex;
    EXPECT_EQ(boundary, 4);
}

TEST(EdgeList, SkipsDegenerateFacesAndEmptyInput) {
    EXPECT_TRUE(build_edge_list({}).empty());
    std::vector<uint32_t> degenerate = {0, 0, 1};
    EXPECT_TRUE(build_edge_list(degenerate).empty());
}
