#pragma once
// Turns raw touch and mouse events into kiosk gestures.
//
// Touch: one finger dragged past the slop orbits; two fingers pinch (zoom by the
// ratio of finger distances) and pan (by the centroid's motion) at the same time;
// two-finger motion is reported once per input frame (events sharing a
// timestamp, as evdev delivers them) so that fingers moving one after the other
// within a frame do not produce a spurious zoom; a short touch that did not move is a tap, and a second tap close in
// time and place is also reported as a double tap. Lifting one of two fingers never turns into an orbit jump: the
// remaining finger's reference is reset.
//
// Mouse (BodyView's desktop bindings, thesis appendix B.2): left drag rotates,
// middle drag pans, right drag zooms (up = closer), the wheel zooms; a plain
// click (no drag) does nothing; Shift+left or Shift+middle click is a Tap with
// its button (the app selects or deselects); Shift+drag with the left or middle button is an object
// drag, which the app turns into moving the selected object when it started on
// the manipulation sphere (left: the X-Z plane, middle: the Y-Z plane).
#include <map>
#include <vector>

#include "kiosk/app/input.h"

namespace body::kiosk {

enum class GestureKind : uint8_t {
    Orbit,      // dx, dy pixels
    Zoom,       // factor (>1 closer)
    Pan,        // dx, dy pixels
    Tap,        // x, y, button (Left for touch; Shift+left or Shift+middle click)
    DoubleTap,  // x, y (follows the Tap of the second touch)
    DragStart,  // x, y, button: Shift+drag began at (x, y)
    Drag,       // dx, dy, button
    DragEnd,
    Begin,  // a finger or button went down (any interaction; resets idle timers)
};

struct Gesture {
    GestureKind kind = GestureKind::Begin;
    double time = 0.0;
    float x = 0.0f, y = 0.0f;    // position (Tap, DoubleTap, DragStart)
    float dx = 0.0f, dy = 0.0f;  // motion (Orbit, Pan, Drag)
    float factor = 1.0f;         // Zoom
    MouseButton button = MouseButton::Left;
};

struct GestureSettings {
    float slop_px = 12.0f;             // movement that turns a touch into a drag
    double tap_seconds = 0.35;         // longest touch that is still a tap
    double double_tap_seconds = 0.40;  // from the first tap's release to the second's
    float double_tap_px = 40.0f;
    float right_drag_zoom_per_px = 0.005f;  // zoom factor exp(-dy * this)
    float wheel_zoom = 1.1f;                // factor per notch
};

class GestureRecognizer {
public:
    explicit GestureRecognizer(GestureSettings settings = {}) : settings_(settings) {}
    // Appends the gestures `event` completes to `out`.
    void feed(const InputEvent& event, std::vector<Gesture>& out);
    // Reports two-finger motion still pending (the app calls this once per frame).
    void flush(std::vector<Gesture>& out);
    void reset();
    int touches() const { return static_cast<int>(touches_.size()); }

private:
    struct Touch {
        float x, y;              // last position
        float start_x, start_y;  // where it went down
        double start_time;
    };
    void touch(const InputEvent& e, std::vector<Gesture>& out);
    void anchor();  // remembers the first two fingers' centroid and spread
    void mouse(const InputEvent& e, std::vector<Gesture>& out);

    GestureSettings settings_;
    std::map<int, Touch> touches_;
    bool moved_ = false;    // the current touch sequence dragged or used two fingers
    bool multi_ = false;    // the current sequence had two or more fingers
    bool pending_ = false;  // two-finger motion not yet reported
    double pending_time_ = 0.0;
    float anchor_cx_ = 0.0f, anchor_cy_ = 0.0f, anchor_d_ = 0.0f;
    double last_tap_time_ = -1e9;
    float last_tap_x_ = 0.0f, last_tap_y_ = 0.0f;
    // Mouse
    bool mouse_down_ = false;
    MouseButton mouse_button_ = MouseButton::Left;
    bool mouse_shift_ = false, mouse_dragging_ = false;
    float mouse_x_ = 0.0f, mouse_y_ = 0.0f, mouse_start_x_ = 0.0f, mouse_start_y_ = 0.0f;
};

}  // namespace body::kiosk
