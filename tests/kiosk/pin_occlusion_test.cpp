// Pins' occlusion rays skip the models they cannot touch (KioskApp::pick_ray):
// the picker walks only the triangles of models whose bounds lie on the line
// of sight before the nearest surface found, and a model in front still hides it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {
namespace {

// A sphere of radius r at c as the "mesh" the picker walks.
std::optional<float> sphere_hit(const Ray& ray, glm::vec3 c, float r) {
    const glm::vec3 oc = ray.origin - c;
    const float b = glm::dot(oc, ray.direction), disc = b * b - (glm::dot(oc, oc) - r * r);
    if (disc < 0.0f) return std::nullopt;
    const float t = -b - std::sqrt(disc);
    return t > 0.0f ? std::optional<float>(t) : std::nullopt;
}

TEST(PinOcclusion, OnlyModelsOnTheLineOfSightAreWalked) {
    // Three spheres in a row; the middle one's pin faces the camera; a fourth sphere sits
    // between the camera and the right one's pin.
    auto scene = scene::parse_scene(R"({"models": [
        {"name": "l", "file": "l.obj"}, {"name": "m", "file": "m.obj", "pins": [{"anchor": [0, 0, 40], "label": {"en": "M"}}]},
        {"name": "r", "file": "r.obj", "pins": [{"anchor": [200, 0, 40], "label": {"en": "R"}}]},
        {"name": "f", "file": "f.obj"}],
        "camera": {"target": [0, 0, 0], "distance": 900}, "kiosk": {"pins": true}})",
                                    "o.json", "");
    ASSERT_TRUE(scene) << scene.error().message;
    const std::vector<glm::vec3> centres{{-200, 0, 0}, {0, 0, 0}, {200, 0, 0}, {170, 0, 300}};
    std::vector<ModelInfo> info;
    for (const glm::vec3& c : centres) info.push_back(ModelInfo{true, c, 40.0f, 10, 10});
    KioskApp app(std::move(scene).value(), info, 1280, 800);
    std::vector<int> walks(4, 0);
    app.set_picker([&](int m, const Ray& ray) {
        ++walks[static_cast<size_t>(m)];
        return sphere_hit(ray, centres[static_cast<size_t>(m)], 40.0f);
    });
    app.update(0.0);  // finds the default pins of l and f, tests occlusion
    ASSERT_EQ(app.pins().size(), 4u);
    std::fill(walks.begin(), walks.end(), 0);
    app.camera().rotate(0.01f, 0.0f);
    app.update(1.0);                    // one occlusion test
    EXPECT_TRUE(app.pins()[1].shown);   // the middle sphere's front pole
    EXPECT_FALSE(app.pins()[2].shown);  // the right one's, behind the fourth sphere
    // Each pin's ray walks its own model, but the right one's only the sphere in
    // front, whose surface is nearer than the right sphere's bounds: 4 walks
    // where every model for every pin would be 16.
    EXPECT_EQ(walks, (std::vector<int>{1, 1, 0, 2}));
}

// With a picker for many rays (the kiosk's: one walk of a model's triangles
// for every pin's ray), each model on some pin's line of sight is called once
// with all those rays, and the pins come out as with one ray at a time.
TEST(PinOcclusion, ManyRaysThroughAModelInOneCall) {
    auto scene = scene::parse_scene(R"({"models": [
        {"name": "l", "file": "l.obj"},
        {"name": "m", "file": "m.obj", "pins": [{"anchor": [0, 0, 40], "label": {"en": "M"}},
                                                {"anchor": [0, 0, -40], "label": {"en": "Back"}},
                                                {"anchor": [0, 40, 0], "label": {"en": "Top"}}]},
        {"name": "r", "file": "r.obj", "pins": [{"anchor": [200, 0, 40], "label": {"en": "R"}}]},
        {"name": "f", "file": "f.obj"}],
        "camera": {"target": [0, 0, 0], "distance": 900}, "kiosk": {"pins": true}})",
                                    "o.json", "");
    ASSERT_TRUE(scene) << scene.error().message;
    const std::vector<glm::vec3> centres{{-200, 0, 0}, {0, 0, 0}, {200, 0, 0}, {170, 0, 300}};
    std::vector<ModelInfo> info;
    for (const glm::vec3& c : centres) info.push_back(ModelInfo{true, c, 40.0f, 10, 10});
    const auto one = [&](int m, const Ray& ray) { return sphere_hit(ray, centres[static_cast<size_t>(m)], 40.0f); };
    KioskApp single(*scene, info, 1280, 800), many(*scene, info, 1280, 800);
    single.set_picker(one);
    many.set_picker(one);
    std::vector<int> calls(4, 0);
    std::vector<size_t> rays_per_call;
    many.set_many_picker([&](int m, std::span<const Ray> rays, std::span<float> nearest) {
        ++calls[static_cast<size_t>(m)];
        rays_per_call.push_back(rays.size());
        for (size_t k = 0; k < rays.size(); ++k)
            if (const auto t = one(m, rays[k])) nearest[k] = std::min(nearest[k], *t);
    });
    for (KioskApp* app : {&single, &many}) app->update(0.0);
    bool any_shown = false, any_hidden = false;
    std::fill(calls.begin(), calls.end(), 0);
    rays_per_call.clear();
    for (int step = 1; step <= 6; ++step) {
        for (KioskApp* app : {&single, &many}) {
            app->camera().rotate(0.4f, 0.0f);
            app->update(static_cast<double>(step));
        }
        ASSERT_EQ(single.pins().size(), many.pins().size());
        for (size_t i = 0; i < single.pins().size(); ++i) {
            EXPECT_EQ(single.pins()[i].shown, many.pins()[i].shown) << "pin " << i << " at step " << step;
            (many.pins()[i].shown ? any_shown : any_hidden) = true;
        }
    }
    // The middle sphere carries three pins: their rays come to it together.
    EXPECT_LE(calls[1], 6);
    EXPECT_GE(*std::max_element(rays_per_call.begin(), rays_per_call.end()), 3u);
    // Some pin was hidden and some shown over the turn (the comparison can tell them apart).
    EXPECT_TRUE(any_shown);
    EXPECT_TRUE(any_hidden);
}

}  // namespace
}  // namespace body::kiosk
