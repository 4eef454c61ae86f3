// The access modes' palettes, icons and toggles (contract in access.h).
#include "kiosk/app/access.h"

#include <cmath>
#include <string>

#include "kiosk/app/text_shaping.h"

namespace body::kiosk {

const Palette& palette(bool high_contrast) {
    // Normal: the overlay's colours since issue 11, unchanged.
    static const Palette normal{{0.12f, 0.11f, 0.10f, 1.0f},
                                {0.12f, 0.11f, 0.10f, 0.35f},
                                {1.0f, 1.0f, 1.0f, 0.85f},
                                {0.80f, 0.88f, 0.97f, 0.92f},
                                {0.12f, 0.11f, 0.10f, 1.0f},
                                {0.35f, 0.35f, 0.40f, 0.9f},
                                false,
                                {1.0f, 1.0f, 0.98f, 0.93f},
                                {0.12f, 0.11f, 0.10f, 1.0f},
                                {0.55f, 0.25f, 0.80f, 1.0f},
                                {1.0f, 1.0f, 1.0f, 0.9f},
                                {0.12f, 0.11f, 0.10f, 1.0f}};
    // High contrast: opaque black boxes, white text, yellow (#FFD700) frames and active controls with black text.
    static const Palette high{{1.0f, 1.0f, 1.0f, 1.0f},
                              {0.62f, 0.62f, 0.62f, 1.0f},
                              {0.0f, 0.0f, 0.0f, 1.0f},
                              {1.0f, 0.843f, 0.0f, 1.0f},
                              {0.0f, 0.0f, 0.0f, 1.0f},
                              {1.0f, 0.843f, 0.0f, 1.0f},
                              true,
                              {0.0f, 0.0f, 0.0f, 1.0f},
                              {1.0f, 1.0f, 1.0f, 1.0f},
                              {1.0f, 0.843f, 0.0f, 1.0f},
                              {0.0f, 0.0f, 0.0f, 1.0f},
                              {1.0f, 0.843f, 0.0f, 1.0f}};
    return high_contrast ? high : normal;
}

const char* control_icon(ControlId id, bool active) {
    switch (id) {
        case ControlId::Home: return "⌂ ";
        case ControlId::Cut: return "✂ ";
        case ControlId::TourStart: return "▶ ";
        case ControlId::TourPrevious: return "◀ ";
        case ControlId::TourPause: return active ? "▶ " : "❚❚ ";
        case ControlId::TourNext: return "▶▶ ";
        case ControlId::TourLeave: return "✕ ";
        default: return "";
    }
}

void add_icons(std::vector<Control>& controls) {
    for (Control& c : controls) c.text.insert(0, control_icon(c.id, c.active));
}

void add_access_controls(const UiState& ui, std::vector<Control>& out) {
    const Rect cell = column_cell(ui, kColumnRows);
    const float gap = std::floor(button_size(ui) * 0.15f), half = (cell.w - gap) * 0.5f;
    const size_t first = out.size();
    for (int i = 0; i < 2; ++i) {
        Control c;
        c.id = i == 0 ? ControlId::Contrast : ControlId::LargeText;
        c.rect = Rect{cell.x + static_cast<float>(i) * (half + gap), cell.y, half, cell.h};
        c.text = i == 0 ? "◐" : "A+";
        c.active = i == 0 ? ui.high_contrast : ui.large_text;
        out.push_back(std::move(c));
    }
    if (is_rtl_language(ui.language)) {
        std::vector<Control> added(out.begin() + static_cast<long>(first), out.end());
        mirror_for_rtl(added, ui.width);
        std::copy(added.begin(), added.end(), out.begin() + static_cast<long>(first));
    }
}

}  // namespace body::kiosk
