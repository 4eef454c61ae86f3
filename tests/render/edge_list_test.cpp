// The edge mesh of the `lines` style.
#include "kiosk/render/edge_list.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

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
// and however many vertex windows its scratch budget splits the walk into,
// with or without count() first.
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
    // Every record of a walk equals the whole list's, field by field.
    const auto expect_whole = [&](const std::vector<EdgeRecord>& got, const std::string& walk) {
        ASSERT_EQ(got.size(), whole.size()) << walk;
        for (size_t i = 0; i < got.size(); ++i) {
            EXPECT_EQ(got[i].v0, whole[i].v0) << walk << ", record " << i;
            EXPECT_EQ(got[i].v1, whole[i].v1) << walk << ", record " << i;
            EXPECT_EQ(got[i].a, whole[i].a) << walk << ", record " << i;
            EXPECT_EQ(got[i].b, whole[i].b) << walk << ", record " << i;
        }
    };
    for (size_t piece : {1u, 2u, 3u, 7u, 64u, 1000u})
        for (size_t scratch : {size_t{4}, size_t{60}, size_t{2} << 20}) {  // one vertex a window .. one window
            std::vector<EdgeRecord> chunk(piece);
            const auto walk = [&](EdgeStream& stream) {
                std::vector<EdgeRecord> out;
                while (size_t n = stream.next(chunk)) out.insert(out.end(), chunk.begin(), chunk.begin() + n);
                return out;
            };
            const std::string where = "piece " + std::to_string(piece) + ", scratch " + std::to_string(scratch);
            EdgeStream stream(idx, scratch);
            EXPECT_EQ(stream.count(), whole.size());
            expect_whole(walk(stream), where);
            // A second walk after restart() hands out the same records again.
            stream.restart();
            expect_whole(walk(stream), "after restart, " + where);
            // Without count() (lines' use: count() is a walk of its own) the same records come.
            EdgeStream uncounted(idx, scratch);
            expect_whole(walk(uncounted), "uncounted, " + where);
        }
}

// Two triangles sharing the edge (0,0,0)-(1,0,0): face 0 in the plane z = 0,
// face 1 turned about the x axis by `degrees` (0: coplanar).
namespace {
struct Hinge {
    body::Vec3f v0{0.0f, 0.0f, 0.0f}, v1{1.0f, 0.0f, 0.0f}, a{0.5f, 1.0f, 0.0f}, b;
    explicit Hinge(float degrees) {
        const float t = glm::radians(degrees);
        b = body::Vec3f(0.5f, -std::cos(t), std::sin(t));
    }
};
}  // namespace

TEST(EdgeList, CoplanarWithinRoundingOfTheCorners) {
    const body::Vec3f none(0.0f);
    EXPECT_TRUE(coplanar_within_rounding(Hinge(0).v0, Hinge(0).v1, Hinge(0).a, Hinge(0).b, none));
    const Hinge fold(1.0f);
    EXPECT_FALSE(coplanar_within_rounding(fold.v0, fold.v1, fold.a, fold.b, none)) << "exact test, 1 degree fold";
    // A grid step of 1/100: corners moved by up to 0.0087 tilt these unit-size
    // faces by up to ~2 degrees each, so a 1 degree fold is within the noise
    // and a 10 degree fold is not.
    const body::Vec3f coarse(0.01f);
    EXPECT_TRUE(coplanar_within_rounding(fold.v0, fold.v1, fold.a, fold.b, coarse));
    const Hinge real(10.0f);
    EXPECT_FALSE(coplanar_within_rounding(real.v0, real.v1, real.a, real.b, coarse));
    // The 16-bit grid of a unit box (step 1/65535) keeps even a 0.1 degree fold.
    const Hinge slight(0.1f);
    EXPECT_FALSE(coplanar_within_rounding(slight.v0, slight.v1, slight.a, slight.b, body::Vec3f(1.0f / 65535.0f)));
    // Degenerate faces have no normal: never coplanar.
    EXPECT_FALSE(coplanar_within_rounding(fold.v0, fold.v1, fold.v0, fold.b, coarse));
}

// Faces that are coplanar before rounding stay coplanar after it: a fine flat
// grid, tilted out of the axes and rounded to a coarse grid, has noisy face
// normals, yet every interior edge is within the rounding bound.
TEST(EdgeList, RoundedFlatGridIsCoplanarEverywhere) {
    const float step = 1.0f / 512.0f;
    const body::Vec3f u = glm::normalize(body::Vec3f(1.0f, 0.3f, 0.2f));
    const body::Vec3f w = glm::normalize(glm::cross(u, body::Vec3f(0.1f, 0.2f, 1.0f)));
    auto at = [&](int i, int j) {
        body::Vec3f p = u * (static_cast<float>(i) * 0.02f) + w * (static_cast<float>(j) * 0.02f);
        return glm::round(p / step) * step;
    };
    int noisy = 0;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            // Quad (i, j) split along its diagonal: the diagonal edge (i,j)-(i+1,j+1).
            const body::Vec3f v0 = at(i, j), v1 = at(i + 1, j + 1), a = at(i + 1, j), b = at(i, j + 1);
            EXPECT_TRUE(coplanar_within_rounding(v0, v1, a, b, body::Vec3f(step))) << i << " " << j;
            noisy += !coplanar_within_rounding(v0, v1, a, b, body::Vec3f(0.0f));
        }
    EXPECT_GT(noisy, 0) << "the rounding should have tilted some faces";
}
