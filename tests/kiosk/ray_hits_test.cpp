// nearest_hits (kiosk/scene/ray_hits.h) against Möller-Trumbore one ray at a
// time: rays from one origin (the pins' case, the edge-plane test) and rays
// from several (the general walk) find the same triangles at the same distance.
#include "kiosk/scene/ray_hits.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace body::kiosk {
namespace {

float reference(const std::vector<glm::vec3>& p, const std::vector<uint32_t>& ix, const Ray& r) {
    float best = INFINITY;
    for (size_t i = 0; i + 2 < ix.size(); i += 3) {
        const glm::vec3 a = p[ix[i]], e1 = p[ix[i + 1]] - a, e2 = p[ix[i + 2]] - a;
        const glm::vec3 pv = glm::cross(r.direction, e2);
        const float det = glm::dot(e1, pv);
        if (std::abs(det) < 1e-12f) continue;
        const glm::vec3 tv = r.origin - a;
        const float u = glm::dot(tv, pv) / det;
        const glm::vec3 qv = glm::cross(tv, e1);
        const float v = glm::dot(r.direction, qv) / det, t = glm::dot(e2, qv) / det;
        if (u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < best) best = t;
    }
    return best;
}

// Random triangles in a box, both windings; rays towards random points of it.
TEST(RayHits, OneOriginAndManyOriginsMatchOneRayAtATime) {
    std::mt19937 rng(27);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<glm::vec3> p;
    std::vector<uint32_t> ix;
    for (uint32_t t = 0; t < 400; ++t) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        for (int k = 0; k < 3; ++k) p.push_back(c + 0.3f * glm::vec3(u(rng), u(rng), u(rng)));
        ix.insert(ix.end(), {3 * t, 3 * t + 1, 3 * t + 2});
    }
    const auto at = [&](uint32_t v) { return p[v]; };
    size_t hits = 0;
    for (int shared_origin = 0; shared_origin < 2; ++shared_origin) {
        std::vector<Ray> rays;
        const glm::vec3 eye(0.3f, -0.2f, 5.0f);
        for (int k = 0; k < 64; ++k) {
            // Some from inside the box: triangles on both sides of the origin.
            const glm::vec3 o = shared_origin ? eye : glm::vec3(u(rng), u(rng), u(rng)) * 3.0f;
            const glm::vec3 target(u(rng), u(rng), u(rng));
            rays.push_back(Ray{o, (target - o) * (0.5f + 0.5f * std::abs(u(rng)))});  // not unit length
        }
        std::vector<float> nearest(rays.size(), INFINITY);
        nearest[3] = 0.5f;  // an earlier, nearer hit is kept
        nearest_hits(ix, at, rays, nearest);
        for (size_t k = 0; k < rays.size(); ++k) {
            const float want = std::min(reference(p, ix, rays[k]), k == 3 ? 0.5f : INFINITY);
            if (std::isinf(want)) {
                EXPECT_TRUE(std::isinf(nearest[k])) << "ray " << k;
            } else {
                EXPECT_NEAR(nearest[k], want, 1e-4f * want) << "ray " << k << " shared origin " << shared_origin;
                ++hits;
            }
        }
    }
    EXPECT_GT(hits, 60u);  // most rays hit something: the comparison means something
    // Rays from inside the cloud: triangles behind the origin are never hit.
    std::vector<Ray> inside{Ray{glm::vec3(0.0f), glm::vec3(0, 0, 1)}, Ray{glm::vec3(0.0f), glm::vec3(0, 0, -1)}};
    std::vector<float> nearest(2, INFINITY);
    nearest_hits(ix, at, inside, nearest);
    for (size_t k = 0; k < 2; ++k) EXPECT_FLOAT_EQ(nearest[k], reference(p, ix, inside[k]));
}

}  // namespace
}  // namespace body::kiosk
