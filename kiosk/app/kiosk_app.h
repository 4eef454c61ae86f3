#pragma once
// The kiosk's state and behaviour, without GL: scene, camera, selection, styles,
// LOD, UI controls and the unattended-kiosk timers. Feed it input events and
// call update() once per frame; the renderer reads the state back. Everything
// is a function of the events and the times passed in, so replays are exact.
//
// Kiosk behaviour:
//   - attract mode after `kiosk.idle_seconds` without input: the camera turns
//     slowly (kAttractRadiansPerSecond) around its target;
//   - after `kiosk.reset_seconds` without input: camera, styles, LOD, group
//     visibility, moved objects, selection and language return to the manifest's;
//   - drift(): a few pixels of slow Lissajous motion of the whole image against
//     burn-in, always on;
//   - no visitor-reachable exit: exit_requested() turns true only after the
//     admin gesture (taps in a corner, from the manifest).
//   - tours (kiosk_tour.cpp, tour.h): a visitor starts, pauses, steps and leaves
//     them with the tour controls; a camera gesture pauses a visitor's tour; the
//     attract mode plays `kiosk.attract_tour` (looping) instead of turning, and
//     any input leaves it. Leaving a tour restores the visibility it changed.
//   - the idle countdown: in the last `kiosk.countdown_seconds` before a reset,
//     once the attract mode has begun after a visitor's input, countdown()
//     gives the whole seconds left (a box on screen); any input cancels it.
//   - pinned labels (kiosk_pins.cpp, pins.h) when `kiosk.pins` is on: pins()
//     per frame, hidden when their point is occluded; a tap opens its card.
//   - with `kiosk.operator_pin`, the admin gesture opens the operator mode
//     (operator_mode.h: PIN keypad, diagnostics, restart) instead of exiting.
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "kiosk/app/camera.h"
#include "kiosk/app/cut_plane.h"
#include "kiosk/app/gestures.h"
#include "kiosk/app/input.h"
#include "kiosk/app/lod_controller.h"
#include "kiosk/app/operator_mode.h"
#include "kiosk/app/pins.h"
#include "kiosk/app/structure_tree.h"
#include "kiosk/app/tour.h"
#include "kiosk/app/tour_cut.h"
#include "kiosk/app/ui.h"
#include "kiosk/scene/scene_models.h"
#include "shared/bvh.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

// What the visitor has set for one model.
struct ModelSettings {
    Style style = Style::Smooth;
    std::optional<float> manual_lod;  // nullopt: automatic
    glm::vec3 offset{0.0f};           // moved with the manipulation sphere
    size_t triangles = 0;             // the level the LOD plan chose (triangle count)
};

struct GroupState {
    bool visible = true;
    std::optional<Style> style;  // last style set for the whole group
};

enum class KioskMode { Interactive, Attract };

// One pinned label in this frame (KioskApp::pins()).
struct PinView {
    int model = -1;
    int pin = -1;                    // index into the model's pins; -1: its default pin
    glm::vec3 anchor{0.0f};          // in the model file's coordinates
    glm::vec2 anchor_px{0.0f};       // on screen (origin top-left)
    bool shown = false;              // in front, on screen, its model visible and the point not occluded
    std::optional<Rect> label;       // where its label is (nullopt: hidden, no room)
    std::string title, description;  // in the current language
};

class KioskApp {
public:
    static constexpr float kAttractRadiansPerSecond = 0.15f;
    static constexpr float kDriftPx = 4.0f;
    static constexpr float kSphereFraction = 0.2f;  // manipulation sphere radius / model radius

    // Returns the ray distance to a model's surface, or nullopt. The default tests
    // the model's bounding sphere; the integration replaces it with triangles.
    // The surface must lie within the model's bounds (ModelInfo, moved by its
    // offset): pick() asks only the models whose bounds the ray enters.
    using Picker = std::function<std::optional<float>(int model, const Ray& ray)>;

    KioskApp(scene::Scene scene, std::vector<ModelInfo> models, int width, int height);

    void set_picker(Picker picker) { picker_ = std::move(picker); }
    // Several rays through one model at once: nearest[k] lowered to ray k's
    // distance to the model's surface (callers fill it with +infinity). When
    // set, the pins' occlusion test casts every pin's ray through a model in
    // one call (one walk of its triangles) instead of one call per pin.
    using ManyPicker = std::function<void(int model, std::span<const Ray> rays, std::span<float> nearest)>;
    void set_many_picker(ManyPicker picker) { many_picker_ = std::move(picker); }
    // The pins' occlusion answered by the renderer's depth buffer (pin_occlusion.h):
    // from then on the app casts no rays for it, and a pin stays hidden until
    // its first answer. set_pin_occlusion gives one answer per pins() entry (1:
    // hidden; another count is ignored); `refresh` re-places the pins and the
    // layout at once (the frame drawn shows its own answer), else the next update() does.
    void take_pin_occlusion_from_renderer() { pin_occlusion_by_renderer_ = true; }
    void set_pin_occlusion(std::span<const char> hidden, bool refresh);
    void set_viewport(int width, int height);
    // The display's density (platform::Surface::pixels_per_mm); 0: unknown. Touch
    // targets are never smaller than kMinTouchMm on it (ui.h).
    void set_pixels_per_mm(float px_per_mm);
    void handle(const InputEvent& event);
    // Advances timers and the camera to `now`, chooses LOD levels for the next frame.
    void update(double now);
    // The frame just drawn (measured or simulated), for the automatic LOD.
    void report_frame(double frame_ms, size_t triangles_drawn) {
        lod_.report_frame(frame_ms, triangles_drawn);
        operator_.note_frame(frame_ms, triangles_drawn);
    }

    // State read back by the renderer and tests.
    const scene::Scene& scene() const { return scene_; }
    const OrbitCamera& camera() const { return camera_; }
    OrbitCamera& camera() { return camera_; }
    int selected() const { return selected_; }
    const ModelSettings& model(int i) const { return models_[static_cast<size_t>(i)]; }
    const ModelInfo& info(int i) const { return info_[static_cast<size_t>(i)]; }
    int model_count() const { return static_cast<int>(models_.size()); }
    const GroupState& group(int i) const { return groups_[static_cast<size_t>(i)]; }
    bool visible(int model) const;
    glm::vec3 model_center(int model) const;  // including the offset
    KioskMode mode() const { return mode_; }
    const std::string& language() const { return language_; }
    bool exit_requested() const { return exit_requested_; }
    int resets() const { return resets_; }
    bool lod_auto() const;  // the selection's LOD (or every model's) is automatic
    bool isolated() const { return isolated_; }
    glm::vec2 drift(double now) const;
    const std::vector<Control>& controls() const { return controls_; }
    UiState ui_state() const;
    const LodController& lod_controller() const { return lod_; }
    size_t triangles_planned() const;
    double last_input() const { return last_input_; }
    // The cut plane (kiosk/app/cut_plane.h) and whether it cuts `model` (its group, or every model).
    const CutPlane& cut() const { return cut_; }
    bool cut_applies(int model) const;
    // The access modes (kiosk/app/access.h): start as the manifest says, visitors toggle them.
    bool high_contrast() const { return high_contrast_; }
    bool large_text() const { return large_text_; }
    // The operator's language set (kiosk_operator.cpp): the manifest's
    // languages, then the UI's others (ui_words.h), each on or off; the
    // language button cycles through those on (scene().kiosk.languages).
    std::vector<std::pair<std::string, bool>> language_set() const;
    void toggle_language(const std::string& language);

    // Actions (also reachable through the controls).
    void select(int model);  // -1 deselects
    void focus(int model, double now);
    void set_model_style(int model, Style style);
    void set_group_style(int group, Style style);
    void set_model_lod(int model, std::optional<float> ratio);
    void set_group_lod(int group, std::optional<float> ratio);
    void set_group_visible(int group, bool visible);
    void toggle_isolate();
    void next_language();
    void home(double now);
    void reset();  // everything back to the manifest's, immediately

    // Tours (kiosk_tour.cpp).
    void start_tour(int tour, double now, bool loop = false);
    void pause_tour(double now);
    void resume_tour(double now);
    void next_tour_step(double now);
    void previous_tour_step(double now);
    void leave_tour();
    const TourPlayer& tour() const { return tour_; }
    std::string tour_caption() const;  // the current step's caption in the current language
    // The idle countdown: whole seconds left before the reset, or nullopt when not shown.
    std::optional<int> countdown() const;
    // Pinned labels (kiosk_pins.cpp): empty unless `kiosk.pins` is on.
    const std::vector<PinView>& pins() const { return pins_; }
    int open_pin() const;                            // index into pins() whose card is open (its model selected), or -1
    const TreeState& tree() const { return tree_; }  // the structure tree (structure_tree.h)
    const OperatorMode& operator_mode() const { return operator_; }
    // A model's placement in the scene: its manifest transform, moved by the visitor.
    glm::mat4 placement(int model) const;
    // The model under pixel (x, y), or -1 (kiosk_pick.cpp: through a box
    // hierarchy over the models, so the picker runs only for those on the ray).
    int pick(float x, float y) const;
    // The visible model nearest along `ray`, or -1; its distance to `distance`.
    int pick_ray(const Ray& ray, float& distance) const;

private:
    void apply_gesture(const Gesture& g);
    void activate(const Control& c, double now);
    void admin_tap(float x, float y, double now);
    void plan_lod();
    void relayout();
    int group_index(int model) const;
    // Tours, countdown and pins (kiosk_tour.cpp, kiosk_pins.cpp).
    void update_tour(double now);
    void enter_tour_step(double now);
    void apply_tour_cut(const scene::TourStep& s);
    void move_tour_cut(float p);
    void tour_gesture(const Gesture& g);
    bool activate_tour(const Control& c, double now);
    void add_tour_and_pin_controls();
    void update_pins(double now);
    void place_pins();
    void find_pin_anchors();
    void test_pin_occlusion();
    std::optional<float> hit_distance(int model, const Ray& ray) const;
    void refresh_pick_tree() const;            // kiosk_pick.cpp
    void activate_operator(const Control& c);  // kiosk_operator.cpp
    // The structure tree (kiosk_tree.cpp).
    bool groups_fit() const;
    TreeContent tree_content() const;
    void add_tree();
    void activate_tree(const Control& c);
    bool tree_key(const InputEvent& e);

    scene::Scene scene_;
    std::vector<ModelInfo> info_;
    std::vector<ModelSettings> models_;
    std::vector<GroupState> groups_;
    OrbitCamera camera_;
    CameraPose home_pose_;
    GestureRecognizer gestures_;
    LodController lod_;
    Picker picker_;
    ManyPicker many_picker_;
    std::vector<Control> controls_;
    std::vector<std::pair<int, ControlId>> ui_touches_;  // touch id -> control it went down on
    int ui_touch_group_ = -1;
    int selected_ = -1;
    bool dragging_object_ = false;
    KioskMode mode_ = KioskMode::Interactive;
    std::string language_;
    bool isolated_ = false;
    std::vector<bool> visible_before_isolate_;
    bool exit_requested_ = false;
    double now_ = 0.0;  // latest time seen
    double last_input_ = 0.0;
    double last_update_ = 0.0;
    bool reset_done_ = false;
    int resets_ = 0;
    std::vector<double> admin_taps_;
    // Tours and countdown.
    TourPlayer tour_;
    CameraPose tour_from_, tour_to_;
    bool tour_moving_ = false;
    bool tour_cut_ = false;         // a step of the running tour set the cut plane (steps[].cut)
    bool tour_cut_moving_ = false;  // the step moves the plane (tour_cut.h) as it moves the camera
    TourCutPose tour_cut_from_, tour_cut_to_;
    std::vector<char> tour_visible_;  // per model while a step sets `visible`; empty: no override
    bool visited_ = false;            // input since the last reset (the countdown is for a visitor)
    // Pins.
    std::vector<PinView> pins_;
    bool pin_anchors_found_ = false;
    std::vector<char> pin_occluded_;
    std::vector<float> pin_tested_key_;  // camera and offsets at the last occlusion test
    std::vector<float> pin_last_key_;    // the same at the last frame
    double pin_tested_at_ = -1e30;
    bool pin_occlusion_by_renderer_ = false;
    int open_pin_ = -1;
    OperatorMode operator_;
    CutPlane cut_;
    float px_per_mm_ = 0.0f;
    bool high_contrast_ = false, large_text_ = false;
    std::vector<std::string> offered_languages_;  // language_set()'s order
    TreeState tree_;                              // the structure tree (kiosk_tree.cpp)
    // Picking (kiosk_pick.cpp): the models' boxes in a hierarchy, built at the
    // first pick and refitted when an offset changed (pick_tree_stale_).
    mutable Bvh pick_tree_;
    mutable std::vector<glm::vec3> pick_lo_, pick_hi_;
    mutable bool pick_tree_built_ = false, pick_tree_stale_ = true;
};

}  // namespace body::kiosk
