// The box hierarchy against a walk over every item: random scenes of spheres,
// random rays, the same nearest item and distance; after moving items (refit).
#include "shared/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace body {
namespace {

struct Spheres {
    std::vector<glm::vec3> centre;
    std::vector<float> radius;
    std::vector<glm::vec3> lo, hi;
    void boxes() {
        lo.resize(centre.size());
        hi.resize(centre.size());
        for (size_t i = 0; i < centre.size(); ++i) lo[i] = centre[i] - radius[i], hi[i] = centre[i] + radius[i];
    }
};

std::optional<float> ray_sphere(const Ray& r, const glm::vec3& c, float radius) {
    const glm::vec3 oc = r.origin - c;
    const float b = glm::dot(oc, r.direction), q = glm::dot(oc, oc) - radius * radius;
    const float disc = b * b - q;
    if (disc < 0.0f) return std::nullopt;
    const float s = std::sqrt(disc);
    if (-b - s >= 0.0f) return -b - s;
    if (-b + s >= 0.0f) return -b + s;
    return std::nullopt;
}

Spheres random_scene(std::mt19937& rng, size_t n, float spread) {
    std::uniform_real_distribution<float> pos(-spread, spread), rad(0.05f, 1.5f);
    Spheres s;
    for (size_t i = 0; i < n; ++i) {
        s.centre.push_back({pos(rng), pos(rng), pos(rng)});
        s.radius.push_back(rad(rng));
    }
    s.boxes();
    return s;
}

Ray random_ray(std::mt19937& rng, float spread) {
    std::uniform_real_distribution<float> pos(-spread, spread);
    std::normal_distribution<float> dir(0.0f, 1.0f);
    Ray r;
    // From around the scene (some from inside) towards a point in it, a little scattered.
    r.origin = glm::vec3(pos(rng), pos(rng), pos(rng)) * 2.0f;
    const glm::vec3 target(pos(rng), pos(rng), pos(rng));
    r.direction = glm::normalize(target - r.origin + 0.1f * spread * glm::vec3(dir(rng), dir(rng), dir(rng)));
    return r;
}

int brute(const Spheres& s, const Ray& r, float& best_t) {
    int best = -1;
    best_t = std::numeric_limits<float>::max();
    for (size_t i = 0; i < s.centre.size(); ++i) {
        const auto t = ray_sphere(r, s.centre[i], s.radius[i]);
        if (t && *t < best_t) best_t = *t, best = static_cast<int>(i);
    }
    return best;
}

int expect_same(const Bvh& bvh, const Spheres& s, std::mt19937& rng, float spread, int rays, size_t* calls_out) {
    int hits = 0;
    size_t calls = 0;
    for (int k = 0; k < rays; ++k) {
        const Ray r = random_ray(rng, spread);
        float tb = 0.0f, tt = 0.0f;
        const int b = brute(s, r, tb);
        const int t = bvh_nearest(
            bvh, r,
            [&](uint32_t i) {
                ++calls;
                return ray_sphere(r, s.centre[i], s.radius[i]);
            },
            tt);
        EXPECT_EQ(b, t) << "ray " << k;
        if (b >= 0) {
            EXPECT_EQ(tb, tt);
            ++hits;
        }
    }
    if (calls_out) *calls_out = calls;
    return hits;
}

TEST(Bvh, NearestMatchesBruteForceOnRandomScenes) {
    std::mt19937 rng(29);
    for (size_t n : {1u, 2u, 3u, 5u, 17u, 100u, 2400u}) {
        const float spread = 2.0f * std::cbrt(static_cast<float>(n));
        const Spheres s = random_scene(rng, n, spread);
        Bvh bvh;
        bvh_build(bvh, s.lo, s.hi);
        size_t calls = 0;
        const int hits = expect_same(bvh, s, rng, spread, 300, &calls);
        if (n >= 100) {
            EXPECT_GT(hits, 30);  // dense enough that the comparison means something
        }
        // The point of the tree: a large scene tests a small share of its items.
        if (n == 2400) {
            EXPECT_LT(calls, 300u * n / 20);
        }
    }
}

// Every item whose box the ray enters before the limit, none other, each once,
// at the distance the slab test gives, after a refit too.
TEST(Bvh, EnteredListsTheBoxesOnTheRayBeforeTheLimit) {
    std::mt19937 rng(31);
    for (size_t n : {1u, 5u, 100u, 2400u}) {
        const float spread = 2.0f * std::cbrt(static_cast<float>(n));
        Spheres s = random_scene(rng, n, spread);
        Bvh bvh;
        bvh_build(bvh, s.lo, s.hi);
        size_t listed_any = 0;
        for (int pass = 0; pass < 2; ++pass) {
            for (int k = 0; k < 200; ++k) {
                const Ray r = random_ray(rng, spread);
                const float before = std::uniform_real_distribution<float>(0.0f, 4.0f * spread)(rng);
                const glm::vec3 inv = 1.0f / r.direction;
                std::vector<float> expected(n, -1.0f), got(n, -1.0f);
                for (size_t i = 0; i < n; ++i)
                    if (const auto t = ray_box(r, inv, s.lo[i], s.hi[i]); t && *t < before) expected[i] = *t;
                bvh_entered(bvh, r, before, [&](uint32_t i, float t) {
                    EXPECT_EQ(got[i], -1.0f) << "item " << i << " listed twice";
                    got[i] = t;
                });
                EXPECT_EQ(got, expected) << "ray " << k << " of " << n << " items";
                listed_any +=
                    static_cast<size_t>(std::count_if(got.begin(), got.end(), [](float t) { return t >= 0; }));
            }
            for (size_t i = 0; i < n; i += 2) s.centre[i] += glm::vec3(spread * 0.3f, 0.0f, -spread * 0.2f);
            s.boxes();
            bvh_refit(bvh, s.lo, s.hi);
        }
        if (n >= 100) {
            EXPECT_GT(listed_any, 100u);  // the rays do reach boxes
        }
    }
}

TEST(Bvh, RefitFollowsMovedItems) {
    std::mt19937 rng(7);
    const float spread = 20.0f;
    Spheres s = random_scene(rng, 500, spread);
    Bvh bvh;
    bvh_build(bvh, s.lo, s.hi);
    std::uniform_real_distribution<float> move(-spread, spread);
    for (size_t i = 0; i < s.centre.size(); i += 3) s.centre[i] += glm::vec3(move(rng), move(rng), move(rng));
    s.boxes();
    bvh_refit(bvh, s.lo, s.hi);
    EXPECT_GT(expect_same(bvh, s, rng, spread, 400, nullptr), 40);
}

TEST(Bvh, EmptyBoxesAndEmptyTrees) {
    Bvh bvh;
    bvh_build(bvh, {}, {});
    float t = 0.0f;
    EXPECT_EQ(bvh_nearest(
                  bvh, Ray{}, [](uint32_t) { return std::optional<float>(1.0f); }, t),
              -1);
    // An item with an empty box (not loaded) is never offered.
    const std::vector<glm::vec3> lo{{-1, -1, -5}, {1, 1, 1}}, hi{{1, 1, -4}, {-1, -1, -1}};
    bvh_build(bvh, lo, hi);
    std::vector<uint32_t> offered;
    const int best = bvh_nearest(
        bvh, Ray{},
        [&](uint32_t i) {
            offered.push_back(i);
            return std::optional<float>(4.0f);
        },
        t);
    EXPECT_EQ(best, 0);
    EXPECT_EQ(offered, std::vector<uint32_t>{0});
}

TEST(Bvh, AxisParallelRays) {
    // Zero direction components: the slab test takes the origin's side.
    const glm::vec3 lo(5, -1, -10), hi(7, 1, -8);
    Ray r;
    r.origin = {6, 0, 0};
    r.direction = {0, 0, -1};
    const glm::vec3 inv = 1.0f / r.direction;
    EXPECT_EQ(ray_box(r, inv, lo, hi), std::optional<float>(8.0f));
    r.origin = {3, 0, 0};
    EXPECT_EQ(ray_box(r, inv, lo, hi), std::nullopt);
    r.origin = {6, 0, -9};  // inside: entered at 0
    EXPECT_EQ(ray_box(r, inv, lo, hi), std::optional<float>(0.0f));
    r.origin = {6, 0, -11};  // past it
    EXPECT_EQ(ray_box(r, inv, lo, hi), std::nullopt);
}

}  // namespace
}  // namespace body
