#pragma once
// The editors of scene.json's keys: one Field per key of the schema table in
// shared/scene/SCENE.md (`key` spelled as the table spells it), each reading its
// value as text and setting it from text. The side panel shows these rows;
// tests/kiosk/author_schema_test.cpp fails on any schema key without one here.
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/scene/scene.h"

namespace body::kiosk::author {

// What a row edits: the scene, a model (and a label language), a group, a
// model's pin (and its label language), a tour (and its title language), a
// tour's step (and its caption language).
enum class FieldScope { Scene, Model, Label, Group, Pin, PinLabel, Tour, TourTitle, Step, StepCaption };

enum class FieldKind {
    Text,    // typed
    Number,  // typed, one number
    Vec3,    // typed, three numbers "x y z"
    Choice,  // a click cycles through choices(); typing works too
    Fixed,   // shown only (the schema allows a single value)
};

struct FieldTarget {
    int model = -1;
    int group = -1;
    int pin = -1;          // with `model`
    int tour = -1;         // FieldScope::Tour, TourTitle, Step, StepCaption
    int step = -1;         // with `tour`
    std::string language;  // FieldScope::Label, PinLabel, TourTitle, StepCaption
    bool operator==(const FieldTarget&) const = default;
};

struct Field {
    const char* key;    // as SCENE.md's table names it, e.g. "models[].colour", "kiosk.admin_gesture"
    const char* label;  // the panel's name for the row
    FieldScope scope;
    FieldKind kind;
    std::string (*get)(const scene::Scene& scene, const FieldTarget& target);
    // Sets the value from `text`; an error names the field and why the text is not a value.
    // The document then checks the whole scene (document.h).
    Status (*set)(scene::Scene& scene, const FieldTarget& target, const std::string& text);
    // Choice: the values a click cycles through (may depend on the scene, e.g. group names).
    std::vector<std::string> (*choices)(const scene::Scene& scene) = nullptr;
};

// Every field, in panel order.
const std::vector<Field>& scene_fields();
// The next choice after `current` (wraps; the first when `current` is not one).
std::string next_choice(const std::vector<std::string>& choices, const std::string& current);

}  // namespace body::kiosk::author
