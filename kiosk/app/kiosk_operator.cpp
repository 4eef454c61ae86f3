// KioskApp's side of the operator mode (operator_mode.h): its controls' actions and the language set.
#include <algorithm>

#include "kiosk/app/kiosk_app.h"

namespace body::kiosk {

void KioskApp::activate_operator(const Control& c) {
    switch (c.id) {  // `c` lives in controls_: read before relayout()
        case ControlId::OperatorKey: operator_.key(c.group); break;
        case ControlId::OperatorRestart:
            operator_.close();
            exit_requested_ = true;  // the service manager starts a fresh kiosk (Restart=always)
            break;
        case ControlId::OperatorClose: operator_.close(); break;
        case ControlId::OperatorLanguage:
            if (c.group >= 0 && c.group < static_cast<int>(offered_languages_.size()))
                toggle_language(offered_languages_[static_cast<size_t>(c.group)]);
            break;
        default: break;
    }
    relayout();
}

std::vector<std::pair<std::string, bool>> KioskApp::language_set() const {
    std::vector<std::pair<std::string, bool>> out;
    const auto& on = scene_.kiosk.languages;
    for (const std::string& l : offered_languages_) out.emplace_back(l, std::find(on.begin(), on.end(), l) != on.end());
    return out;
}

// The set keeps the offered order and at least one language; the first on is
// the one a reset returns to, and a visitor's language switched off gives way
// to it now. Until the kiosk restarts (the manifest is not written).
void KioskApp::toggle_language(const std::string& language) {
    auto& on = scene_.kiosk.languages;
    const auto it = std::find(on.begin(), on.end(), language);
    if (it != on.end()) {
        if (on.size() == 1) return;
        on.erase(it);
    } else {
        const auto set = language_set();
        on.clear();
        for (const auto& [l, was_on] : set)
            if (was_on || l == language) on.push_back(l);
    }
    if (std::find(on.begin(), on.end(), language_) == on.end()) language_ = on.front();
}

}  // namespace body::kiosk
