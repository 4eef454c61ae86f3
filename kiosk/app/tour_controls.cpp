// Tour buttons, the caption box and the countdown box (contract in tour_controls.h).
#include "kiosk/app/tour_controls.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/ui_words.h"

namespace body::kiosk {

namespace {

Control make(ControlId id, const Rect& r, std::string text, int group = -1, bool active = false) {
    Control c;
    c.id = id;
    c.group = group;
    c.rect = r;
    c.text = std::move(text);
    c.active = active;
    return c;
}

}  // namespace

std::string tour_text(const std::string& key, const std::string& language) { return ui_word(key, language); }

void add_tour_controls(const UiState& ui, const TourUiState& st, std::vector<Control>& out) {
    const float b = button_size(ui);
    const float gap = std::floor(b * 0.15f);
    const float width = static_cast<float>(ui.width), height = static_cast<float>(ui.height);
    const float top = gap + ui.drift_y;
    const std::string& L = ui.language;
    // Rows are centred in the room left of the controls already in the two top rows (ui.h's columns).
    float right = width;
    for (const Control& c : out) {
        if (c.rect.y < top + 2.0f * b + gap && c.rect.x > width * 0.25f) right = std::min(right, c.rect.x);
    }
    const float room = std::max(b, right - gap - ui.drift_x);
    auto row = [&](size_t n, float w) {
        const float total = static_cast<float>(n) * w + static_cast<float>(n > 0 ? n - 1 : 0) * gap;
        return (room - total) * 0.5f + ui.drift_x;
    };
    if (st.playing && !st.attract) {
        const float w =
            std::max(min_target_px(ui), std::min(std::floor(b * 1.6f), std::floor((room - 5.0f * gap) / 4.0f)));
        float x = row(4, w);
        const ControlId ids[] = {ControlId::TourPrevious, ControlId::TourPause, ControlId::TourNext,
                                 ControlId::TourLeave};
        const std::string words[] = {tour_text("back", L), tour_text(st.paused ? "play" : "pause", L),
                                     tour_text("next", L), tour_text("leave", L)};
        for (size_t i = 0; i < 4; ++i) {
            out.push_back(make(ids[i], Rect{x, top, w, b}, words[i], -1, i == 1 && st.paused));
            x += w + gap;
        }
    } else if (!st.playing && !st.tour_titles.empty()) {
        const float w = std::floor(b * 2.2f);
        const size_t fit = static_cast<size_t>(std::max(1.0f, (room - gap) / (w + gap)));
        const size_t n = std::min(st.tour_titles.size(), fit);
        float x = row(n, w);
        for (size_t i = 0; i < n; ++i) {
            out.push_back(make(ControlId::TourStart, Rect{x, top, w, b}, st.tour_titles[i], static_cast<int>(i)));
            x += w + gap;
        }
    }
    if (st.playing && !st.caption.empty()) {
        const float w = std::floor(std::min(room - 2.0f * gap, b * 8.0f));
        const float y = st.attract ? top : top + b + gap;
        out.push_back(make(ControlId::TourCaption, Rect{(room - w) * 0.5f + ui.drift_x, y, w, b}, st.caption));
    }
    if (st.countdown) {
        const float w = std::floor(std::min(width * 0.5f, b * 5.0f)), h = std::floor(b * 1.4f);
        out.push_back(make(ControlId::Countdown,
                           Rect{(width - w) * 0.5f + ui.drift_x, (height - h) * 0.5f + ui.drift_y, w, h},
                           tour_text("still", L) + " " + std::to_string(*st.countdown), -1, true));
    }
}

}  // namespace body::kiosk
