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

// The streamed walk hands out the same records in the same order whatever the
// piece size (including pieces that end in the middle of a vertex's corners)
// and however many vertex windows its scratch budget splits the walk into.
TEST(EdgeList, StreamInPiecesMatchesTheWholeList) {
    // A 6x5 grid of quads, two triangles each, with one degenerate face.
    std::vector<uint32_t> idx;
    const uint32_t w = 7;
    for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 0; x < 6; ++x) {
            const uint32_t a = y * w + x, b = a + 1, c = a + w, d = c + 1;
            idx.insert(idx.end(), {a, b, d, a, d, c});
        }
    idx.insert(idx.end(), {3, 3, 4});
    const auto whole = build_edge_list(idx);
    ASSERT_EQ(whole.size(), 6u * 6 + 5u * 7 + 30u);  // horizontal + vertical + diagonal edges
    for (size_t piece : {1u, 2u, 3u, 7u, 64u, 1000u})
        for (size_t scratch : {size_t{4}, size_t{60}, size_t{2} << 20}) {  // one vertex a window .. one window
            EdgeStream stream(idx, scratch);
            EXPECT_EQ(stream.count(), whole.size());
            std::vector<EdgeRecord> out, chunk(piece);
            while (size_t n = stream.next(chunk)) out.insert(out.end(), chunk.begin(), chunk.begin() + n);
            ASSERT_EQ(out.size(), whole.size()) << "piece " << piece << ", scratch " << scratch;
            // A second walk after restart() hands out the same records again.
            stream.restart();
            std::vector<EdgeRecord> again;
            while (size_t n = stream.next(chunk)) again.insert(again.end(), chunk.begin(), chunk.begin() + n);
            ASSERT_EQ(again.size(), whole.size()) << "after restart, piece " << piece << ", scratch " << scratch;
            for (size_t i = 0; i < out.size(); ++i) {
                EXPECT_EQ(out[i].v0, whole[i].v0);
                EXPECT_EQ(out[i].v1, whole[i].v1);
                EXPECT_EQ(out[i].a, whole[i].a);
                EXPECT_EQ(out[i].b, whole[i].b);
                EXPECT_EQ(again[i].v0, whole[i].v0);
                EXPECT_EQ(again[i].b, whole[i].b);
            }
        }
}
