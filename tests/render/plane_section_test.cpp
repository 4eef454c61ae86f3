// The section of a mesh by a plane (kiosk/render/plane_section.h): closed
// loops on the plane, of the right length, from float positions and from
// quantized codes alike.
#include "kiosk/render/plane_section.h"

#include <gtest/gtest.h>

#include <map>
#include <tuple>

using namespace body;
using namespace body::render;

namespace {

// The unit cube [0,1]^3, 8 corners, 12 outward triangles.
const float kCube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const uint32_t kCubeFaces[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};

// Each endpoint must be met an even number of times (the segments close into
// loops; a loop through a vertex on the plane may meet it more than once).
void expect_closed(const std::vector<Vec3f>& segments) {
    std::map<std::tuple<float, float, float>, int> seen;
    for (const Vec3f& p : segments) ++seen[{p.x, p.y, p.z}];
    for (const auto& [p, n] : seen)
        EXPECT_EQ(n % 2, 0) << std::get<0>(p) << " " << std::get<1>(p) << " " << std::get<2>(p);
}

float length(const std::vector<Vec3f>& segments) {
    float sum = 0.0f;
    for (size_t i = 0; i + 1 < segments.size(); i += 2) sum += glm::length(segments[i + 1] - segments[i]);
    return sum;
}

}  // namespace

TEST(PlaneSection, CubeCutAcrossIsAClosedSquare) {
    std::vector<Vec3f> segments;
    std::vector<float> scratch;
    const glm::vec4 plane(0.0f, 0.0f, 1.0f, -0.3f);
    EXPECT_EQ(plane_section(&kCube[0][0], 3, 8, kCubeFaces, 36, plane, segments, scratch), 8u);
    for (const Vec3f& p : segments) EXPECT_NEAR(p.z, 0.3f, 1e-6f);
    EXPECT_NEAR(length(segments), 4.0f, 1e-5f);
    expect_closed(segments);
}

TEST(PlaneSection, TiltedPlaneAndPlaneOffTheMesh) {
    std::vector<Vec3f> segments;
    std::vector<float> scratch;
    const Vec3f n = glm::normalize(Vec3f(1.0f, 1.0f, 1.0f));
    plane_section(&kCube[0][0], 3, 8, kCubeFaces, 36, glm::vec4(n, -glm::dot(n, Vec3f(0.5f))), segments, scratch);
    // Through the centre, normal to the diagonal: a regular hexagon of side sqrt(2)/2.
    EXPECT_NEAR(length(segments), 6.0f * std::sqrt(2.0f) / 2.0f, 1e-5f);
    for (const Vec3f& p : segments) EXPECT_NEAR(glm::dot(n, p - Vec3f(0.5f)), 0.0f, 1e-6f);
    expect_closed(segments);
    segments.clear();
    EXPECT_EQ(plane_section(&kCube[0][0], 3, 8, kCubeFaces, 36, glm::vec4(0, 0, 1, -2), segments, scratch), 0u);
    EXPECT_TRUE(segments.empty());
}

TEST(PlaneSection, PlaneThroughVerticesStaysClosed) {
    // z = 1 is the top face: its vertices count as kept (not above), nothing is crossed;
    // x = 1 - y through two corners of the top and bottom faces cuts the cube in two prisms.
    std::vector<Vec3f> segments;
    std::vector<float> scratch;
    EXPECT_EQ(plane_section(&kCube[0][0], 3, 8, kCubeFaces, 36, glm::vec4(0, 0, 1, -1), segments, scratch), 0u);
    const Vec3f n = glm::normalize(Vec3f(1.0f, 1.0f, 0.0f));
    plane_section(&kCube[0][0], 3, 8, kCubeFaces, 36, glm::vec4(n, -glm::dot(n, Vec3f(1, 0, 0))), segments, scratch);
    expect_closed(segments);
    EXPECT_GT(segments.size(), 0u);
}

TEST(PlaneSection, QuantizedCodesAndSkippedTriangles) {
    uint16_t codes[8][3];
    for (int v = 0; v < 8; ++v)
        for (int k = 0; k < 3; ++k) codes[v][k] = static_cast<uint16_t>(kCube[v][k] * 1000.0f + 7.0f);
    std::vector<Vec3f> segments;
    std::vector<float> scratch;
    plane_section(&codes[0][0], 3, 8, kCubeFaces, 36, glm::vec4(0, 0, 1, -507.0f), segments, scratch);
    EXPECT_NEAR(length(segments), 4000.0f, 1e-2f);
    expect_closed(segments);
    // A triangle naming a vertex past the count is skipped, not read.
    const uint32_t bad[6] = {0, 1, 99, 0, 2, 1};
    segments.clear();
    EXPECT_EQ(plane_section(&codes[0][0], 3, 8, bad, 6, glm::vec4(0, 0, 1, -507.0f), segments, scratch), 0u);
}
