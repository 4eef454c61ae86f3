#pragma once
// Reader for the scene.json keys of the kiosk's access modes (schema in
// SCENE.md: kiosk.high_contrast, kiosk.large_text, kiosk.access_buttons,
// kiosk.icons), called from scene.cpp. Internal to shared/scene; fails as
// scene_tours.h's readers do.
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "shared/scene/scene.h"
#include "shared/scene/scene_tours.h"

namespace body::scene::detail {

// Only those keys of `kiosk` are read; each must be true or false.
bool read_kiosk_access_settings(const nlohmann::json& kiosk, const std::string& path, KioskSettings& k, Failure& f);

}  // namespace body::scene::detail
