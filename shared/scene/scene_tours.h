#pragma once
// Readers for the scene.json keys of tours, pinned labels and the kiosk's
// attract tour, countdown and pin switch (schema in SCENE.md), called from
// scene.cpp. Internal to shared/scene. Each returns false with `where` (the
// JSON path) and `why` (the reason) set; scene.cpp turns them into its
// one-line "<file>: <path>: <reason>" message.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "shared/scene/scene.h"

namespace body::scene::detail {

struct Failure {
    std::string where, why;
};

// models[i].pins
bool read_pins(const nlohmann::json& v, const std::string& path, std::vector<Pin>& out, Failure& f);
// kiosk.attract_tour, kiosk.countdown_seconds, kiosk.pins, kiosk.operator_pin (only those keys of `kiosk` are read).
bool read_kiosk_tour_settings(const nlohmann::json& kiosk, const std::string& path, KioskSettings& k, Failure& f);
// The root's `tours`.
bool read_tours(const nlohmann::json& v, const std::string& path, std::vector<Tour>& out, Failure& f);
// After models, groups and languages are known: names in steps exist, languages
// are listed (empty languages become the default), tour names are unique, the
// attract tour exists.
bool check_tour_references(Scene& s, Failure& f);

}  // namespace body::scene::detail
