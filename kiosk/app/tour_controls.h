#pragma once
// The controls of tours and of the idle countdown, as a layout (no GL), added
// after ui.h's controls:
//   - no tour playing: one start button per tour (its title) in a row at the
//     top, centred left of the controls already in `out` (ui.h's columns; as
//     many as fit);
//   - a tour playing: back, pause/play, next and leave in that row, the step's
//     caption in a wide box under it;
//   - the "still looking?" countdown: a wide box in the middle of the screen
//     with the seconds left before the reset (any touch cancels it).
#include <optional>
#include <string>
#include <vector>

#include "kiosk/app/ui.h"

namespace body::kiosk {

struct TourUiState {
    std::vector<std::string> tour_titles;  // in the current language
    bool playing = false;                  // a tour is active (paused or not)
    bool paused = false;
    bool attract = false;          // the attract mode's tour: no visitor controls, caption only
    std::string caption;           // the step's caption; empty: none shown
    std::optional<int> countdown;  // seconds left before the reset
};

// Appends the tour controls and the countdown for `state` to `out`, which holds layout_controls()'s.
void add_tour_controls(const UiState& ui, const TourUiState& state, std::vector<Control>& out);
// A tour or countdown word in `language` ("tour", "back", "pause", "play", "next", "leave", "still"); English fallback.
std::string tour_text(const std::string& key, const std::string& language);

}  // namespace body::kiosk
