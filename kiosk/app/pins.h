#pragma once
// Pinned labels' layout, no GL: each label is put beside its anchor (the pin's
// point on screen) so that no two labels overlap, no label overlaps a UI
// control (or any other obstacle) or another pin's anchor, and every label lies
// inside the screen. A label that has no such place is hidden (the kiosk never
// lets labels collide; fewer labels show on a crowded screen).
//
// Deterministic: candidates are tried in a fixed order (up-right, up-left,
// down-right, down-left, right, left, up, down; at 1, 2 and 3 leader lengths),
// pins in the order given (the caller puts the most important first). Pixels,
// origin top-left.
#include <glm/glm.hpp>
#include <optional>
#include <span>
#include <vector>

#include "kiosk/app/ui.h"

namespace body::kiosk {

struct PinRequest {
    glm::vec2 anchor{0.0f};  // the pin's point on screen
    glm::vec2 size{0.0f};    // its label's width and height
};

// True when the rectangles, each grown by gap / 2, intersect.
bool rects_overlap(const Rect& a, const Rect& b, float gap = 0.0f);

// One entry per request: the label's rectangle, or nullopt (hidden).
std::vector<std::optional<Rect>> layout_pins(std::span<const PinRequest> pins, std::span<const Rect> obstacles,
                                             const Rect& screen, float leader_px, float gap_px);

// Where a leader line from `anchor` meets `label`: the label's nearest point.
glm::vec2 leader_end(const Rect& label, const glm::vec2& anchor);

}  // namespace body::kiosk
