#pragma once
// Internal to kiosk/author's editors (fields.cpp, fields_tours.cpp): the text
// parsers and choice lists they share, and the tour and pin editors'
// parts that fields.cpp assembles into scene_fields().
#include <array>
#include <string>
#include <vector>

#include "kiosk/author/fields.h"

namespace body::kiosk::author::detail {

std::string fmt(float v);                         // shortest "%g"
std::string fmt3(const std::array<float, 3>& v);  // "x y z"
Status parse_number(const std::string& text, const char* what, float& out);
Status parse_vec3(const std::string& text, const char* what, std::array<float, 3>& out);
Status parse_lod(const std::string& text, const char* what, scene::Lod& out);
std::string lod_text(const scene::Lod& l);
Status parse_style_text(const std::string& text, const char* what, Style& out);
std::vector<std::string> style_choices(const scene::Scene& s);
std::vector<std::string> bool_choices(const scene::Scene& s);

// models[].pins: a pin's anchor, and its title and description per language.
std::vector<Field> pin_fields();
// kiosk.attract_tour, kiosk.countdown_seconds, kiosk.pins, kiosk.operator_pin.
std::vector<Field> kiosk_tour_fields();
// tours, tours[].name/title/steps, steps[].*.
std::vector<Field> tour_fields();
// kiosk.high_contrast, kiosk.large_text, kiosk.access_buttons, kiosk.icons (fields_access.cpp).
std::vector<Field> kiosk_access_fields();

// A model or group renamed from `from` to `to`: tour steps naming it follow.
void rename_in_tours(scene::Scene& s, const std::string& from, const std::string& to);
// Languages no longer listed: pin labels, tour titles and captions in them go
// (a pin left without any gets its model's name in the first language).
void drop_tour_languages(scene::Scene& s, const std::vector<std::string>& languages);

}  // namespace body::kiosk::author::detail
