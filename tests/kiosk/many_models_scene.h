#pragma once
// A scene of many models in many groups for the body-scale kiosk tests:
// `groups` groups named "<word> N" (twelve words, so that their first letters
// vary), `per_group` models each; spheres on a jittered grid.
#include <random>
#include <string>
#include <vector>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk::test {

inline std::string many_models_json(int groups, int per_group) {
    static const char* kWords[] = {"Arcuate", "Basal",   "Caudate", "Dentate", "Frontal", "Gyrus",
                                   "Insula",  "Lingual", "Medial",  "Nucleus", "Optic",   "Pallidum"};
    std::string models, list;
    for (int g = 0; g < groups; ++g) {
        const std::string gname = std::string(kWords[g % 12]).append(" ").append(std::to_string(g));
        list += g ? ",{\"name\": \"" : "{\"name\": \"";
        list += gname;
        list += "\"}";
        for (int m = 0; m < per_group; ++m) {
            const std::string name = gname + "_m" + std::to_string(m);
            models += models.empty() ? "{\"name\": \"" : ",{\"name\": \"";
            models += name;
            models += "\", \"file\": \"";
            models += name;
            models += ".obj\", \"group\": \"";
            models += gname;
            models += "\", \"label\": {\"en\": \"";
            models += kWords[(g + m) % 12];
            models += " ";
            models += std::to_string(m);
            models += "\"}}";
        }
    }
    std::string json = "{\"models\": [";
    json += models;
    json += "], \"groups\": [";
    json += list;
    json += "], \"camera\": {\"azimuth_deg\": 0, \"polar_deg\": 90}, \"kiosk\": {\"languages\": [\"en\", \"de\"]}}";
    return json;
}

// Model infos for that scene: centres on a jittered cube grid, radii 0.3..1.2 of the spacing.
inline std::vector<ModelInfo> many_models_info(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(-0.4f, 0.4f), radius(0.3f, 1.2f);
    const int side = static_cast<int>(std::ceil(std::cbrt(static_cast<double>(count))));
    std::vector<ModelInfo> info;
    for (size_t i = 0; i < count; ++i) {
        const int x = static_cast<int>(i) % side, y = static_cast<int>(i) / side % side,
                  z = static_cast<int>(i) / (side * side);
        const glm::vec3 c = glm::vec3(x + jitter(rng), y + jitter(rng), z + jitter(rng)) * 10.0f;
        info.push_back(ModelInfo{true, c, radius(rng) * 10.0f * 0.5f, 1000, 100});
    }
    return info;
}

inline KioskApp make_many_app(int groups, int per_group, uint32_t seed = 1) {
    auto scene = scene::parse_scene(many_models_json(groups, per_group), "many.json", "");
    if (!scene) ADD_FAILURE() << scene.error().message;
    return KioskApp(std::move(scene).value(), many_models_info(size_t(groups * per_group), seed), 1280, 800);
}

}  // namespace body::kiosk::test
