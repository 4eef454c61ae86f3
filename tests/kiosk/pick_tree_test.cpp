// KioskApp::pick through the box hierarchy (kiosk_pick.cpp) against a walk over
// every visible model with the same picker: random pixels on a many-model
// scene, after a model is dragged (refit) and after a group is hidden.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kiosk/app/replay.h"
#include "many_models_scene.h"

namespace body::kiosk {
namespace {

std::optional<float> sphere_hit(const Ray& ray, const glm::vec3& c, float r) {
    const glm::vec3 oc = ray.origin - c;
    const float b = glm::dot(oc, ray.direction), q = glm::dot(oc, oc) - r * r, disc = b * b - q;
    if (disc < 0.0f) return std::nullopt;
    const float t = -b - std::sqrt(disc);
    return t >= 0.0f ? std::optional<float>(t) : std::nullopt;
}

struct Counted {
    KioskApp& app;
    size_t calls = 0;
    std::optional<float> operator()(int m, const Ray& ray) {
        ++calls;
        return sphere_hit(ray, app.model_center(m), app.info(m).radius);
    }
};

int brute_pick(const KioskApp& app, float x, float y) {
    const Ray ray = app.camera().ray(x, y);
    int best = -1;
    float best_t = 1e30f;
    for (int i = 0; i < app.model_count(); ++i) {
        if (!app.visible(i)) continue;
        const auto t = sphere_hit(ray, app.model_center(i), app.info(i).radius);
        if (t && *t < best_t) best_t = *t, best = i;
    }
    return best;
}

glm::vec2 on_screen(const KioskApp& app, const glm::vec3& p) {
    const glm::vec4 c = app.camera().projection() * app.camera().view() * glm::vec4(p, 1.0f);
    return {(c.x / c.w * 0.5f + 0.5f) * 1280.0f, (0.5f - c.y / c.w * 0.5f) * 800.0f};
}

// Compares `rays` pixels near random models' centres (some off every model);
// returns how many hit a model.
int compare(KioskApp& app, std::mt19937& rng, int rays) {
    std::uniform_int_distribution<int> model(0, app.model_count() - 1);
    std::uniform_real_distribution<float> jitter(-25.0f, 25.0f);
    int hits = 0;
    for (int k = 0; k < rays; ++k) {
        const glm::vec2 p = on_screen(app, app.model_center(model(rng)));
        const float px = p.x + jitter(rng), py = p.y + jitter(rng);
        const int expected = brute_pick(app, px, py);
        EXPECT_EQ(app.pick(px, py), expected) << "pixel " << px << "," << py;
        hits += expected >= 0;
    }
    return hits;
}

TEST(PickTree, MatchesEveryModelWalkOnAManyModelScene) {
    KioskApp app = test::make_many_app(40, 30);  // 1,200 models
    Counted counted{app};
    app.set_picker([&](int m, const Ray& ray) { return counted(m, ray); });
    app.update(0.0);
    std::mt19937 rng(29);
    EXPECT_GT(compare(app, rng, 300), 100);
    // The tree's point: the picker runs for a small share of the models.
    EXPECT_LT(counted.calls, 300u * 1200u / 20u);

    // Drag a model (Shift+drag from its centre): the tree is refitted.
    const int moved = 600;
    app.select(moved);
    const glm::vec2 s = on_screen(app, app.model_center(moved));
    const float sx = s.x, sy = s.y;
    const std::string from = std::to_string(sx) + " " + std::to_string(sy) + " shift\n";
    const std::string to = std::to_string(sx + 300) + " " + std::to_string(sy - 200) + " shift\n";
    std::string text = "1.0 mouse-down left ";
    text += from;
    text += "1.1 mouse-move ";
    text += to;
    text += "1.2 mouse-up left ";
    text += to;
    auto r = parse_replay(text, "drag.replay");
    ASSERT_TRUE(r);
    run_replay(app, *r, 60.0, 1.0);
    ASSERT_GT(glm::length(app.model(moved).offset), 10.0f);
    EXPECT_GT(compare(app, rng, 300), 100);
    // At its new place it is picked where the walk over every model picks it.
    const glm::vec2 n = on_screen(app, app.model_center(moved));
    EXPECT_EQ(app.pick(n.x, n.y), brute_pick(app, n.x, n.y));

    // Hidden models are not picked.
    for (int g = 0; g < 20; ++g) app.set_group_visible(g, false);
    EXPECT_GT(compare(app, rng, 300), 50);
}

}  // namespace
}  // namespace body::kiosk
