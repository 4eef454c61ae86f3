#pragma once
// A three-model scene for the kiosk tests: "left" and "middle" in group
// "limbic", "right" in group "cortex"; spheres of radius 40 at x = -100, 0, 100.
#include <string>
#include <vector>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/replay.h"

namespace body::kiosk::test {

inline const char* kTestScene = R"({
  "models": [
    {"name": "left", "file": "left.obj", "group": "limbic", "label": {"en": "Left", "de": "Links"}},
    {"name": "middle", "file": "middle.obj", "group": "limbic",
     "label": {"en": {"title": "Middle", "description": "The one in the middle"}}},
    {"name": "right", "file": "right.obj", "group": "cortex", "style": "hatching"}
  ],
  "groups": [{"name": "limbic"}, {"name": "cortex"}],
  "camera": {"azimuth_deg": 0, "polar_deg": 90},
  "kiosk": {"idle_seconds": 5, "reset_seconds": 10, "languages": ["en", "de"]}
})";

inline KioskApp make_app(size_t full_triangles = 100000, size_t base_triangles = 1000) {
    auto scene = scene::parse_scene(kTestScene, "test.json", "");
    std::vector<ModelInfo> info;
    for (float x : {-100.0f, 0.0f, 100.0f})
        info.push_back(ModelInfo{true, {x, 0, 0}, 40.0f, full_triangles, base_triangles});
    return KioskApp(std::move(scene).value(), std::move(info), 1280, 800);
}

inline Replay replay(const std::string& text) {
    auto r = parse_replay(text, "test.replay");
    if (!r) {
        ADD_FAILURE() << r.error().message;
        return {};
    }
    return std::move(r).value();
}

}  // namespace body::kiosk::test
