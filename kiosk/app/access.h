#pragma once
// The kiosk's access modes (issue 27 item 5; scene.json kiosk.high_contrast,
// kiosk.large_text, kiosk.access_buttons, kiosk.icons in SCENE.md), as layout
// and colour rules without GL:
//   - the 2-D layer's palette: the normal one, or high contrast (white on
//     black, yellow frames and active controls: 21:1 and 19.6:1 contrast);
//   - large text: the overlay's text kLargeTextScale times larger, buttons
//     kLargeButtonScale (ui.h) times larger so it fits;
//   - the visitors' two toggles (contrast ◐, large text A+) as the next row of
//     the control column;
//   - icons beside the words a visitor looks for first (Home, Cut, tours):
//     glyphs of DejaVu Sans, the kiosk's first font, so no image is needed.
// KioskApp keeps the modes' state (reset to the manifest's with the rest);
// the overlay and the leader lines draw with them.
#include <vector>

#include "kiosk/app/batch_2d.h"
#include "kiosk/app/ui.h"

namespace body::kiosk {

inline constexpr float kLargeTextScale = 1.4f;

struct Palette {
    Rgba ink, faded;         // control text, disabled control text
    Rgba fill, active_fill;  // control backgrounds
    Rgba active_ink;         // text on active_fill
    Rgba edge;               // the control's edge line (high contrast: a frame all round)
    bool framed;             // edge on all four sides, not only below
    Rgba card, card_ink, accent;
    Rgba line_halo, line_ink;  // leader lines
};

const Palette& palette(bool high_contrast);

// The icon shown before the text of a control (UTF-8, with the space), or
// empty: Home ⌂, Cut ✂, TourStart ▶, TourPrevious ◀, TourPause ❚❚ (▶ while
// paused: `active`), TourNext ▶▶, TourLeave ✕.
const char* control_icon(ControlId id, bool active);
// Puts each control's icon before its text.
void add_icons(std::vector<Control>& controls);
// The contrast and large-text toggles (ControlId::Contrast, ::LargeText) as two
// half-width buttons in the column's row after the cut plane's (mirrored for
// right-to-left languages as the rest of the column).
void add_access_controls(const UiState& ui, std::vector<Control>& out);

}  // namespace body::kiosk
