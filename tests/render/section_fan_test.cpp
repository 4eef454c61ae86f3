// The section's even-odd triangles with one apex per grid cell
// (kiosk/render/section_fan.h): a point of the plane is covered an odd number
// of times exactly when it lies inside the outlines (holes and touching loops
// included), whatever the segments' order and direction, and the triangles
// stay near their cells instead of reaching across the section.
#include "kiosk/render/section_fan.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace body;
using namespace body::render;

namespace {

using Loop = std::vector<glm::vec2>;

// A star-shaped loop of `n` points around `c`, radius r(1 + a sin(k t)).
Loop star(glm::vec2 c, float r, float a, int k, int n) {
    Loop loop;
    for (int i = 0; i < n; ++i) {
        const float t = 6.2831853f * static_cast<float>(i) / static_cast<float>(n);
        const float radius = r * (1.0f + a * std::sin(static_cast<float>(k) * t));
        loop.push_back(c + radius * glm::vec2(std::cos(t), std::sin(t)));
    }
    return loop;
}

// Even-odd inside test over every loop (crossings of a ray toward +x).
bool inside(const std::vector<Loop>& loops, glm::vec2 p) {
    bool in = false;
    for (const Loop& l : loops)
        for (size_t i = 0, j = l.size() - 1; i < l.size(); j = i++)
            if ((l[i].y > p.y) != (l[j].y > p.y) &&
                p.x < l[j].x + (l[i].x - l[j].x) * (p.y - l[j].y) / (l[i].y - l[j].y))
                in = !in;
    return in;
}

float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// Whether p is inside triangle (a, b, c) (either orientation), and its least
// distance to the triangle's edges (samples too close to an edge are skipped).
bool in_triangle(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c, float& edge_distance) {
    const glm::vec2 v[3] = {a, b, c};
    int positive = 0, negative = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::vec2 e = v[(i + 1) % 3] - v[i];
        const float s = cross(e, p - v[i]);
        const float len = glm::length(e);
        if (len > 0.0f) {
            const float t = std::clamp(glm::dot(p - v[i], e) / (len * len), 0.0f, 1.0f);
            edge_distance = std::min(edge_distance, glm::length(p - (v[i] + t * e)));
        }
        positive += s > 0.0f;
        negative += s < 0.0f;
    }
    return positive == 3 || negative == 3;
}

struct Plane {
    Vec3f n, u, v, origin;
    Vec3f at(glm::vec2 p) const { return origin + u * p.x + v * p.y; }
    glm::vec2 on(Vec3f p) const { return {glm::dot(p - origin, u), glm::dot(p - origin, v)}; }
};

// The loops' segments on the plane, each loop point computed once (shared
// ends are the same floats, as plane_section gives them), in shuffled order
// and direction.
std::vector<Vec3f> segments_of(const std::vector<Loop>& loops, const Plane& plane, std::mt19937& rng) {
    std::vector<std::pair<Vec3f, Vec3f>> pairs;
    for (const Loop& l : loops) {
        std::vector<Vec3f> points;
        for (glm::vec2 p : l) points.push_back(plane.at(p));
        for (size_t i = 0; i < points.size(); ++i) pairs.emplace_back(points[i], points[(i + 1) % points.size()]);
    }
    std::shuffle(pairs.begin(), pairs.end(), rng);
    std::vector<Vec3f> segments;
    for (auto& [a, b] : pairs) {
        if (rng() & 1) std::swap(a, b);
        segments.insert(segments.end(), {a, b});
    }
    return segments;
}

// Covers random points of the loops' box and beyond with the fan's triangles
// and compares the count's parity with the even-odd inside test.
void expect_even_odd(const std::vector<Loop>& loops, int cells, std::mt19937& rng) {
    const Vec3f n = glm::normalize(Vec3f(0.3f, -0.5f, 0.8f));
    const Vec3f u = glm::normalize(glm::cross(n, Vec3f(1.0f, 0.0f, 0.0f))), v = glm::cross(n, u);
    const Plane plane{n, u, v, n * 2.5f};
    const std::vector<Vec3f> segments = segments_of(loops, plane, rng);
    glm::vec2 lo(INFINITY), hi(-INFINITY);
    for (const Vec3f& p : segments) {
        lo = glm::min(lo, glm::vec2(glm::dot(p, u), glm::dot(p, v)));
        hi = glm::max(hi, glm::vec2(glm::dot(p, u), glm::dot(p, v)));
    }
    std::vector<Vec3f> fan;
    SectionFanScratch scratch;
    const size_t triangles = section_fan(segments, n, u, v, lo, hi, cells, fan, scratch);
    ASSERT_EQ(fan.size(), triangles * 3);
    ASSERT_GE(triangles, segments.size() / 2);
    for (const Vec3f& p : fan) ASSERT_NEAR(glm::dot(p, n), 2.5f, 1e-4f);  // on the plane
    std::vector<glm::vec2> flat;
    for (const Vec3f& p : fan) flat.push_back(plane.on(p));
    glm::vec2 box_lo(INFINITY), box_hi(-INFINITY);
    for (const Loop& l : loops)
        for (glm::vec2 p : l) box_lo = glm::min(box_lo, p), box_hi = glm::max(box_hi, p);
    std::uniform_real_distribution<float> x(box_lo.x - 0.2f, box_hi.x + 0.2f), y(box_lo.y - 0.2f, box_hi.y + 0.2f);
    int checked = 0, in = 0;
    for (int s = 0; s < 1500; ++s) {
        const glm::vec2 p(x(rng), y(rng));
        float edge = INFINITY;
        int count = 0;
        for (size_t t = 0; t + 2 < flat.size(); t += 3)
            count += in_triangle(p, flat[t], flat[t + 1], flat[t + 2], edge);
        if (edge < 1e-3f) continue;
        ++checked;
        in += inside(loops, p);
        ASSERT_EQ(count % 2 == 1, inside(loops, p)) << "at " << p.x << " " << p.y << " with " << cells << " cells";
    }
    EXPECT_GT(checked, 1100);
    EXPECT_GT(in, 40);
}

}  // namespace

TEST(SectionFan, OddCountExactlyInsideTheOutlines) {
    std::mt19937 rng(27);
    const std::vector<Loop> one{star({0.0f, 0.0f}, 1.0f, 0.4f, 5, 300)};
    const std::vector<Loop> with_hole{star({0.0f, 0.0f}, 1.0f, 0.3f, 3, 400), star({0.1f, 0.0f}, 0.35f, 0.2f, 4, 90)};
    const std::vector<Loop> apart{star({-1.5f, 0.0f}, 0.6f, 0.5f, 7, 200), star({1.2f, 0.4f}, 0.8f, 0.1f, 2, 150)};
    for (int cells : {1, 2, 7, 32})
        for (const auto* loops : {&one, &with_hole, &apart}) expect_even_odd(*loops, cells, rng);
}

TEST(SectionFan, LoopsThatTouchAtAPoint) {
    // Two squares meeting at a corner: four segments end at the shared point.
    std::mt19937 rng(5);
    const std::vector<Loop> touching{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {{1, 1}, {2, 1}, {2, 2}, {1, 2}}};
    for (int cells : {1, 3, 8}) expect_even_odd(touching, cells, rng);
}

TEST(SectionFan, TrianglesStayNearTheirCells) {
    // With g cells a side, a segment's triangle reaches at most one cell's
    // diagonal from its segment; only the joins reach the box's centre, and
    // there are far fewer of them than segments.
    std::mt19937 rng(3);
    const Vec3f n(0.0f, 0.0f, 1.0f), u(1.0f, 0.0f, 0.0f), v(0.0f, 1.0f, 0.0f);
    const Plane plane{n, u, v, Vec3f(0.0f)};
    const std::vector<Loop> loops{star({0.0f, 0.0f}, 1.0f, 0.2f, 3, 2000)};
    const std::vector<Vec3f> segments = segments_of(loops, plane, rng);
    const int cells = section_fan_cells(segments.size() / 2);
    EXPECT_GT(cells, 8);
    std::vector<Vec3f> fan;
    SectionFanScratch scratch;
    section_fan(segments, n, u, v, glm::vec2(-1.2f), glm::vec2(1.2f), cells, fan, scratch);
    const float diagonal = 2.4f / static_cast<float>(cells) * std::sqrt(2.0f);
    size_t long_ones = 0;
    for (size_t t = 0; t + 2 < fan.size(); t += 3) {
        const float reach = std::max(
            {glm::length(fan[t] - fan[t + 1]), glm::length(fan[t] - fan[t + 2]), glm::length(fan[t + 1] - fan[t + 2])});
        long_ones += reach > 2.0f * diagonal;
    }
    EXPECT_LT(long_ones, segments.size() / 2 / 8);
    EXPECT_LT(fan.size() / 3, segments.size() / 2 * 5 / 4);
}
