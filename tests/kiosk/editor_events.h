#pragma once
// The authoring editor driven by events, as the window feeds it: what the
// editor unit tests share.
#include <gtest/gtest.h>

#include <string>

#include "kiosk/author/editor.h"

namespace body::kiosk::author::events {

inline InputEvent key(int k, uint32_t mods = 0) {
    InputEvent e;
    e.type = InputEvent::Type::Key;
    e.key = k;
    e.pressed = true;
    e.modifiers = mods;
    return e;
}

inline void type(Editor& ed, const std::u32string& text) {
    for (char32_t c : text) {
        InputEvent e;
        e.type = InputEvent::Type::Text;
        e.key = static_cast<int>(c);
        ed.handle(e);
    }
}

// Clicks the middle of the value box of the field row called `label` (or the row itself).
inline void click(Editor& ed, const std::string& label, uint32_t mods = 0) {
    for (const PanelRow& r : ed.rows()) {
        if (r.text != label) continue;
        const Rect& b = r.kind == RowKind::Field ? r.value_rect : r.rect;
        InputEvent e;
        e.type = InputEvent::Type::MouseDown;
        e.x = b.x + b.w * 0.5f;
        e.y = b.y + b.h * 0.5f;
        e.modifiers = mods;
        EXPECT_TRUE(ed.handle(e)) << label;
        return;
    }
    ADD_FAILURE() << "no panel row '" << label << "'";
}

}  // namespace body::kiosk::author::events
