// Pins' occlusion rays skip the models they cannot touch (the models' box
// hierarchy, kiosk_pick.cpp): the picker walks only the triangles of models
// whose bounds lie on the line of sight before the pin, nearest first, a pin
// hidden by a near model is not cast through the ones behind, and a model in
// front still hides it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

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

// Three spheres of radius 40 in a row (l, m, r) and a fourth (f) between the
// camera and r's pin; `m_pins` the middle one's pins (JSON), r's pin on its front.
struct FourSpheres {
    scene::Scene scene;
    std::vector<glm::vec3> centres{{-200, 0, 0}, {0, 0, 0}, {200, 0, 0}, {170, 0, 300}};
    std::vector<ModelInfo> info;
    std::optional<float> hit(int m, const Ray& ray) const {
        return sphere_hit(ray, centres[static_cast<size_t>(m)], 40.0f);
    }
};

FourSpheres four_spheres(const std::string& m_pins) {
    FourSpheres f;
    auto scene = scene::parse_scene(R"({"models": [
        {"name": "l", "file": "l.obj"}, {"name": "m", "file": "m.obj", "pins": )" +
                                        m_pins + R"(},
        {"name": "r", "file": "r.obj", "pins": [{"anchor": [200, 0, 40], "label": {"en": "R"}}]},
        {"name": "f", "file": "f.obj"}],
        "camera": {"target": [0, 0, 0], "distance": 900}, "kiosk": {"pins": true}})",
                                    "o.json", "");
    EXPECT_TRUE(scene) << scene.error().message;
    if (scene) f.scene = std::move(scene).value();
    for (const glm::vec3& c : f.centres) f.info.push_back(ModelInfo{true, c, 40.0f, 10, 10});
    return f;
}

TEST(PinOcclusion, OnlyModelsOnTheLineOfSightAreWalked) {
    // The middle sphere's pin faces the camera; the fourth sphere hides the right one's.
    const FourSpheres s = four_spheres(R"([{"anchor": [0, 0, 40], "label": {"en": "M"}}])");
    ASSERT_EQ(s.scene.models.size(), 4u);
    KioskApp app(s.scene, s.info, 1280, 800);
    std::vector<int> walks(4, 0);
    app.set_picker([&](int m, const Ray& ray) {
        ++walks[static_cast<size_t>(m)];
        return s.hit(m, ray);
    });
    app.update(0.0);  // finds the default pins of l and f, tests occlusion
    ASSERT_EQ(app.pins().size(), 4u);
    std::fill(walks.begin(), walks.end(), 0);
    app.camera().rotate(0.01f, 0.0f);
    app.update(1.0);                    // one occlusion test
    EXPECT_TRUE(app.pins()[1].shown);   // the middle sphere's front pole
    EXPECT_FALSE(app.pins()[2].shown);  // the right one's, behind the fourth sphere
    // Each pin's ray walks its own model, but the right one's only the sphere in
    // front: that hides it, so the right sphere (entered later on the ray) is
    // never walked. 4 walks where every model for every pin would be 16.
    EXPECT_EQ(walks, (std::vector<int>{1, 1, 0, 2}));
}

// With a picker for many rays (the kiosk's: one walk of a model's triangles
// for every pin's ray), each model on some pin's line of sight is called once
// with all those rays, and the pins come out as with one ray at a time.
TEST(PinOcclusion, ManyRaysThroughAModelInOneCall) {
    const FourSpheres s = four_spheres(R"([{"anchor": [0, 0, 40], "label": {"en": "M"}},
        {"anchor": [0, 0, -40], "label": {"en": "Back"}}, {"anchor": [0, 40, 0], "label": {"en": "Top"}}])");
    ASSERT_EQ(s.scene.models.size(), 4u);
    const auto one = [&](int m, const Ray& ray) { return s.hit(m, ray); };
    KioskApp single(s.scene, s.info, 1280, 800), many(s.scene, s.info, 1280, 800);
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
