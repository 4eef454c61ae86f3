#pragma once
// On-screen controls sized for fingers, as a layout and hit-testing model (no
// GL): the renderer draws the rectangles and texts it returns; the app routes a
// touch that lands on a control to it instead of to the gestures.
//
// Layout (pixels, origin top-left): a column of buttons along the right edge —
// home, language, style of the selection, style of its group, LOD -, LOD +, LOD
// auto, isolate group — and a row of group show/hide toggles along the bottom.
// For a right-to-left language (is_rtl_language) the layout is mirrored: the
// column on the left, the group row from the right. Buttons are at least kMinButtonPx (about 9 mm on a 24" 1080p panel)
// and grow with the screen. Hit tests accept touches up to kTouchSlopPx outside a button when no other button is
// closer.
#include <string>
#include <vector>

namespace body::kiosk {

struct Rect {
    float x = 0, y = 0, w = 0, h = 0;
    bool contains(float px, float py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

enum class ControlId {
    Home,
    Language,
    Style,
    GroupStyle,
    LodDown,
    LodUp,
    LodAuto,
    Isolate,
    GroupToggle,
    // Tours, the idle countdown and pinned labels (kiosk/app/tour_controls.h); `group` holds the
    // tour index (TourStart) or the pin index into KioskApp::pins() (Pin).
    TourStart,
    TourPrevious,
    TourPause,
    TourNext,
    TourLeave,
    TourCaption,
    Countdown,
    Pin,
    // The operator mode (kiosk/app/operator_mode.h); `group` holds the key (OperatorKey).
    OperatorKey,
    OperatorInfo,
    OperatorRestart,
    OperatorClose,
    OperatorLanguage,  // a language of the set on or off; `group` its index in KioskApp::language_set()
    Cut,               // the cut plane: off -> move the plane -> move the camera -> off (kiosk/app/cut_plane.h)
    CutAxis,           // the plane's preset: axial -> coronal -> sagittal
    Contrast,          // the access modes (kiosk/app/access.h): high contrast on/off
    LargeText,         // large text on/off
    // The structure tree (kiosk/app/structure_tree.h), in place of the group row when it does not fit.
    TreeOpen,       // the row's one button: opens and closes the panel
    TreeSearch,     // the letters typed so far; a tap clears them
    TreeBackspace,  // removes the last letter
    TreeUp,         // the list a page up
    TreeDown,       // the list a page down
    TreeLetter,     // a letter key; `group` holds the letter (a Unicode code point, lower case)
    TreeGroup,      // a group's row; `group` its index: shows/hides it, as its toggle does, and opens it
    TreeModel,      // a model's row; `group` the model's index: selects it
};

struct Control {
    ControlId id = ControlId::Home;
    int group = -1;  // GroupToggle: index into the scene's groups; TourStart, Pin: see ControlId
    Rect rect;
    std::string text;  // UTF-8, in the current language
    bool enabled = true;
    bool active = false;  // toggles that are on (group visible, isolate on, LOD auto)
};

struct UiState {
    int width = 1280, height = 800;
    std::string language = "en";
    bool has_selection = false;
    bool selection_has_group = false;
    bool lod_auto = true;
    bool isolated = false;
    std::string style_name;        // style of the selection (shown on the button)
    std::string group_style_name;  // style of the selection's group
    std::vector<std::string> group_names;
    std::vector<bool> group_visible;
    float drift_x = 0.0f, drift_y = 0.0f;            // anti burn-in offset, pixels
    bool cut_on = false, cut_editing = false;        // the cut plane (kiosk/app/cut_plane.h)
    std::string cut_axis = "axial";                  // its preset (cut_axis_name)
    float px_per_mm = 0.0f;                          // the display's density; 0: unknown (pixel minimum only)
    bool high_contrast = false, large_text = false;  // the access modes (kiosk/app/access.h)
    bool access_buttons = false;                     // their toggles follow the column
};

inline constexpr float kMinButtonPx = 64.0f;
inline constexpr float kMinTouchMm = 9.0f;  // a fingertip: no touch target is smaller on either side
inline constexpr float kTouchSlopPx = 8.0f;
inline constexpr float kLargeButtonScale = 1.25f;  // button_size with large text (access.h)
inline constexpr int kColumnRows = 9;              // rows layout_controls fills in the control column

std::vector<Control> layout_controls(const UiState& state);
// Mirrors the controls left to right in a screen `width` pixels wide.
void mirror_for_rtl(std::vector<Control>& controls, int width);
// The control at (x, y), or nullptr; disabled controls are never hit.
const Control* hit_test(const std::vector<Control>& controls, float x, float y);
// The smallest side of any touch target in pixels: kMinButtonPx, and kMinTouchMm
// when the display's density is known.
float min_target_px(const UiState& state);
// The side of a control in pixels: a finger's size, at least min_target_px
// (kLargeButtonScale times that with large text).
float button_size(const UiState& state);
// The control column's cell `row` (0: the top; rows that do not fit above the
// group row flow into further columns to the left), before RTL mirroring.
Rect column_cell(const UiState& state, int row);
// A UI word in `language` ("home", "language", "style", "group", "lod", "auto", "isolate", "cut", "off",
// "move", "fixed", "axial", "coronal", "sagittal"): en, de, fr, es, ru, el, ar, he, zh, ja; English fallback.
std::string ui_text(const std::string& key, const std::string& language);

}  // namespace body::kiosk
