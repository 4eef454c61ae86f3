#pragma once
// The scene manifest `scene.json` (schema in shared/scene/SCENE.md): which models
// a kiosk shows, how they are grouped, styled and labelled, where the camera
// starts and how the kiosk behaves when nobody touches it.
//
// Contract: parse_scene() never throws; every error message reads
// "<file>: <json path>: <reason>", e.g. "scene.json: models[2].colour: expected 3 numbers in [0,1]".
// Model file paths are returned resolved against the manifest's directory
// (`Model::path`) next to the text as written (`Model::file`).
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/style.h"

namespace body::scene {

// Level of detail: a fixed ratio of the full triangle count in (0, 1], or automatic
// (the kiosk's LOD controller decides).
struct Lod {
    bool automatic = true;
    float ratio = 1.0f;
    bool operator==(const Lod&) const = default;
};

struct Transform {
    std::array<float, 3> translate{0, 0, 0};   // scene units (millimetres)
    std::array<float, 3> rotate_deg{0, 0, 0};  // Euler angles, applied X then Y then Z
    float scale = 1.0f;                        // uniform
    bool operator==(const Transform&) const = default;
};

struct LabelText {
    std::string language;  // e.g. "en"
    std::string title;     // UTF-8
    std::string description;
};

// A pinned label (kiosk/app/pins.h): a point on the model's surface, in the
// model file's coordinates (before `transform`), and its text per language.
struct Pin {
    std::array<float, 3> anchor{0, 0, 0};
    std::vector<LabelText> labels;  // at least one; languages from KioskSettings::languages
};

struct Model {
    std::string name;   // unique in the scene
    std::string file;   // as written in the manifest
    std::string path;   // `file` resolved against the manifest directory
    std::string group;  // empty: no group
    std::array<float, 3> colour{0.8f, 0.8f, 0.8f};
    Transform transform;
    Style style = Style::Smooth;
    Lod lod;
    std::vector<LabelText> labels;  // at least one; languages from KioskSettings::languages
    std::vector<Pin> pins;          // empty: the kiosk's default pin when KioskSettings::pins is on
};

struct Group {
    std::string name;
    std::optional<Style> style;  // overrides the models' styles when set
    std::optional<Lod> lod;      // overrides the models' LOD when set
    bool visible = true;
};

struct HomeCamera {
    std::array<float, 3> target{0, 0, 0};
    float azimuth_deg = 0.0f;  // around +Y, 0 looks down -Z
    float polar_deg = 90.0f;   // from +Y; 90 is the horizon
    float distance = 0.0f;     // 0: fit the scene's bounds when loaded
    float fov_deg = 40.0f;
};

// The one way out of the kiosk for staff: `taps` taps within `seconds` inside the
// corner square of `corner_size` (fraction of the screen's shorter side).
struct AdminGesture {
    enum class Corner { TopLeft, TopRight, BottomLeft, BottomRight };
    Corner corner = Corner::TopLeft;
    int taps = 5;
    float seconds = 3.0f;
    float corner_size = 0.08f;
};

struct KioskSettings {
    float idle_seconds = 30.0f;                // attract mode after this long without input
    float reset_seconds = 120.0f;              // full reset after this long without input
    std::vector<std::string> languages{"en"};  // first = default
    AdminGesture admin;
    float frame_ms_target = 16.7f;    // LOD controller target
    std::string attract_tour;         // tour the attract mode plays (looping) instead of turning; empty: turn
    float countdown_seconds = 10.0f;  // "still looking?" countdown before the reset; 0: none
    bool pins = false;                // show pinned labels (each model's pins, else its default pin)
    std::string operator_pin;         // digits: the admin gesture opens the operator mode; empty: it exits
    // Access modes (SCENE.md): the start state of high contrast and large text, the visitors'
    // buttons that toggle them, icons beside the control words.
    bool high_contrast = false, large_text = false, access_buttons = false, icons = false;
};

// Tours (kiosk/app/tour.h): named, ordered steps the camera and the scene's
// state move through. Names in `visible`, `styles` and `select` are model or
// group names.
enum class Easing { Linear, EaseIn, EaseOut, EaseInOut };

struct TourCamera {  // a missing value keeps the previous step's
    std::optional<std::array<float, 3>> target;
    std::optional<float> azimuth_deg, polar_deg, distance;
};

// A tour step's cut plane (steps[].cut): a preset's normal (its world normal
// as CutPlaneSettings gives it) or a world normal, pointing into the removed
// half, and the plane's signed distance from the scene's centre along it.
struct TourCut {
    int axis = -1;  // 0 axial, 1 coronal, 2 sagittal; -1: `normal`
    std::array<float, 3> normal{0.0f, 1.0f, 0.0f};
    float offset = 0.0f;
};

struct TourStep {
    TourCamera camera;
    std::optional<std::vector<std::string>> visible;  // shown; the rest hidden. nullopt: as the manifest
    std::vector<std::pair<std::string, Style>> styles;
    std::string select;              // model name; empty: nothing selected
    std::vector<LabelText> caption;  // title per language (description unused); may be empty
    float duration = 2.0f;           // seconds the transition into this step takes
    float hold = 4.0f;               // seconds the step stays before the next one (when playing)
    Easing easing = Easing::EaseInOut;
    std::optional<TourCut> cut;  // the plane during the step; nullopt: none (see SCENE.md)
};

struct Tour {
    std::string name;              // unique
    std::vector<LabelText> title;  // the start button's text per language; default: the name
    std::vector<TourStep> steps;   // at least one
};

// The kiosk's cut plane (kiosk/app/cut_plane.h): the world normals of its
// presets, axial, coronal and sagittal, for bundles whose world is not the
// exhibits' (+Y superior, +Z anterior, +X left); nullopt keeps that default.
struct CutPlaneSettings {
    std::array<std::optional<std::array<float, 3>>, 3> axes;  // axial, coronal, sagittal
    // The input slices the plane snaps to: world planes dot(slice_normal, p) =
    // slices[i]; slice_normal nullopt: the axial preset's normal.
    std::vector<float> slices;
    std::optional<std::array<float, 3>> slice_normal;
    // The grey-level volume shown on the caps (shared/scene/slice_volume.h),
    // as written, and resolved against the manifest's directory; empty: none.
    std::string volume, volume_path;
    // The volume's image also on the plane around the caps, within its bounds.
    bool volume_around = false;
};

struct Scene {
    std::string source;  // manifest path as given
    std::string base_dir;
    std::vector<Model> models;
    std::vector<Group> groups;
    HomeCamera camera;
    KioskSettings kiosk;
    std::vector<Tour> tours;
    CutPlaneSettings cut_plane;

    const Group* find_group(const std::string& name) const;
    int model_index(const std::string& name) const;  // -1 when absent
    // The label in `language`, else in the default language, else the first one.
    const LabelText& label(const Model& model, const std::string& language) const;
    // The same fallback for any list of texts (pins, captions); nullptr when `texts` is empty.
    const LabelText* text(const std::vector<LabelText>& texts, const std::string& language) const;
    int tour_index(const std::string& name) const;  // -1 when absent
};

// Parses manifest text; `source` names the file in messages and `base_dir`
// resolves model paths ("" = current directory).
Result<Scene> parse_scene(const std::string& text, const std::string& source, const std::string& base_dir);
// Reads and parses a manifest file.
Result<Scene> read_scene(const std::string& path);

}  // namespace body::scene
