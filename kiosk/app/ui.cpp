// Finger-sized controls: layout and hit testing (their words: ui_words.h).
#include "kiosk/app/ui.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/text_shaping.h"
#include "kiosk/app/ui_words.h"

namespace body::kiosk {

float min_target_px(const UiState& s) {
    return std::max(kMinButtonPx, std::ceil(kMinTouchMm * std::max(0.0f, s.px_per_mm)));
}

float button_size(const UiState& s) {
    const float b = std::max(min_target_px(s), std::floor(static_cast<float>(std::min(s.width, s.height)) / 11.0f));
    return s.large_text ? std::floor(b * kLargeButtonScale) : b;
}

Rect column_cell(const UiState& s, int row) {
    const float b = button_size(s);
    const float gap = std::floor(b * 0.15f);
    const float wide = b * 2.2f;
    const float top = gap + s.drift_y;
    const float bottom = static_cast<float>(s.height) - b - 2.0f * gap + s.drift_y;
    const int rows_per_column = std::max(1, static_cast<int>((bottom - top + gap) / (b + gap)));
    const int column = row / rows_per_column;
    return Rect{static_cast<float>(s.width) - static_cast<float>(column + 1) * (wide + gap) + s.drift_x,
                top + static_cast<float>(row % rows_per_column) * (b + gap), wide, b};
}

std::string ui_text(const std::string& key, const std::string& language) { return ui_word(key, language); }

std::vector<Control> layout_controls(const UiState& s) {
    const float b = button_size(s);
    const float gap = std::floor(b * 0.15f);
    const float wide = b * 2.2f;
    // Rows of the right-hand column (column_cell).
    int row = 0;
    float x = 0.0f, y = 0.0f;
    std::vector<Control> out;
    auto place = [&] {
        const Rect cell = column_cell(s, row++);
        x = cell.x;
        y = cell.y;
    };
    auto add = [&](ControlId id, std::string text, bool enabled, bool active, float w = 0.0f) {
        Control c;
        c.id = id;
        c.rect = Rect{x, y, w > 0 ? w : wide, b};
        c.text = std::move(text);
        c.enabled = enabled;
        c.active = active;
        out.push_back(std::move(c));
    };
    const std::string& L = s.language;
    place();
    add(ControlId::Home, ui_text("home", L), true, false);
    place();
    std::string lang = s.language;
    std::transform(lang.begin(), lang.end(), lang.begin(), [](char c) { return static_cast<char>(std::toupper(c)); });
    add(ControlId::Language, lang, true, false);
    place();
    add(ControlId::Style, ui_text("style", L) + ": " + s.style_name, s.has_selection, false);
    place();
    add(ControlId::GroupStyle, ui_text("group", L) + ": " + s.group_style_name, s.selection_has_group, false);
    place();
    const float half = (wide - gap) * 0.5f;
    add(ControlId::LodDown, "−", !s.lod_auto || s.has_selection, false, half);
    add(ControlId::LodUp, "+", !s.lod_auto || s.has_selection, false, half);
    out.back().rect.x = x + half + gap;
    place();
    add(ControlId::LodAuto, ui_text("lod", L) + ": " + ui_text("auto", L), true, s.lod_auto);
    place();
    add(ControlId::Isolate, ui_text("isolate", L), s.selection_has_group || s.isolated, s.isolated);

    // Group toggles along the bottom, left to right, leaving the right column free.
    float gx = gap + s.drift_x;
    const float gy = static_cast<float>(s.height) - b - gap + s.drift_y;
    // As wide as 2.4 buttons, narrower when many groups share the row, never
    // below a button; groups that still do not fit are left out.
    const float n = static_cast<float>(std::max<size_t>(s.group_names.size(), 1));
    const float gw = std::max(
        min_target_px(s), std::min(std::floor(b * 2.4f), std::floor((static_cast<float>(s.width) - gap) / n - gap)));
    for (size_t i = 0; i < s.group_names.size(); ++i) {
        if (gx + gw > static_cast<float>(s.width)) break;
        Control c;
        c.id = ControlId::GroupToggle;
        c.group = static_cast<int>(i);
        c.rect = Rect{gx, gy, gw, b};
        c.text = s.group_names[i];
        c.active = i < s.group_visible.size() && s.group_visible[i];
        out.push_back(std::move(c));
        gx += gw + gap;
    }
    // The cut plane's buttons continue the column (after the group row in `out`).
    const char* cut_state = !s.cut_on ? "off" : s.cut_editing ? "move" : "fixed";
    place();
    add(ControlId::Cut, ui_text("cut", L) + ": " + ui_text(cut_state, L), true, s.cut_on);
    place();
    add(ControlId::CutAxis, ui_text(s.cut_axis, L), s.cut_on, false);
    if (is_rtl_language(s.language)) mirror_for_rtl(out, s.width);
    return out;
}

void mirror_for_rtl(std::vector<Control>& controls, int width) {
    for (Control& c : controls) c.rect.x = static_cast<float>(width) - c.rect.x - c.rect.w;
}

const Control* hit_test(const std::vector<Control>& controls, float x, float y) {
    const Control* best = nullptr;
    float best_d = kTouchSlopPx;
    for (const Control& c : controls) {
        if (!c.enabled) continue;
        const float dx = std::max({c.rect.x - x, 0.0f, x - (c.rect.x + c.rect.w)});
        const float dy = std::max({c.rect.y - y, 0.0f, y - (c.rect.y + c.rect.h)});
        const float d = std::hypot(dx, dy);
        if (d == 0.0f) return &c;
        if (d <= best_d) {
            best = &c;
            best_d = d;
        }
    }
    return best;
}

}  // namespace body::kiosk
