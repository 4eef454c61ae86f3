#pragma once
// The label card: the selected model's title and description in the visitor's
// language, in a card at the bottom left above the group row. overlay.cpp
// draws it (shrunk to its text, bottom edge kept).
#include <string>

#include "kiosk/app/ui.h"

namespace body::kiosk {

class KioskApp;

struct LabelCard {
    bool visible = false;
    Rect rect;
    std::string title;        // UTF-8
    std::string description;  // UTF-8
};

// The card's largest rectangle (bottom-left, above the group row; bottom-right for a right-to-left language).
Rect label_card_rect(const UiState& state);
// The card for the app's selection (not visible when nothing is selected).
LabelCard label_card(const KioskApp& app);

}  // namespace body::kiosk
