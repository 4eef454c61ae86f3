// The label card's content and place (contract in label_card.h).
#include "kiosk/app/label_card.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/text_shaping.h"

namespace body::kiosk {

Rect label_card_rect(const UiState& s) {
    const float b = button_size(s);
    const float gap = std::floor(b * 0.15f);
    const float w = std::min(static_cast<float>(s.width) * 0.45f, 560.0f);
    const float h = std::min(static_cast<float>(s.height) * 0.3f, 240.0f);
    Rect r{gap + s.drift_x, static_cast<float>(s.height) - b - 2 * gap - h + s.drift_y, w, h};
    if (is_rtl_language(s.language)) r.x = static_cast<float>(s.width) - r.x - r.w;  // mirrored with the controls
    return r;
}

LabelCard label_card(const KioskApp& app) {
    LabelCard card;
    if (app.selected() < 0) return card;
    const scene::Model& m = app.scene().models[static_cast<size_t>(app.selected())];
    const scene::LabelText& t = app.scene().label(m, app.language());
    card.visible = true;
    card.rect = label_card_rect(app.ui_state());
    card.title = t.title;
    card.description = t.description;
    if (const int pin = app.open_pin(); pin >= 0) {  // a tapped pin's card: the pin's text
        card.title = app.pins()[static_cast<size_t>(pin)].title;
        card.description = app.pins()[static_cast<size_t>(pin)].description;
    }
    return card;
}

}  // namespace body::kiosk
