// The app's side of the structure tree (structure_tree.h): when the groups do
// not fit the bottom row, the row's toggles give way to the tree; its keys,
// the keyboard's letters and its rows act on the app's state.
#include <algorithm>

#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/structure_tree.h"

namespace body::kiosk {

// The group row's rule (ui.cpp), at the drift's largest shift so that the
// choice does not flicker as the drift moves the row.
bool KioskApp::groups_fit() const {
    if (groups_.empty()) return true;
    UiState s = ui_state();
    s.drift_x = kDriftPx;
    size_t toggles = 0;
    for (const Control& c : layout_controls(s)) toggles += c.id == ControlId::GroupToggle;
    return toggles == groups_.size();
}

TreeContent KioskApp::tree_content() const {
    TreeContent content;
    content.selected_model = selected_;
    for (size_t g = 0; g < groups_.size(); ++g)
        content.groups.push_back(TreeGroupEntry{scene_.groups[g].name, groups_[g].visible, {}});
    for (int m = 0; m < model_count(); ++m) {
        const int g = group_index(m);
        if (g < 0 || !info_[static_cast<size_t>(m)].loaded) continue;
        const scene::LabelText& label = scene_.label(scene_.models[static_cast<size_t>(m)], language_);
        const std::string& title = label.title.empty() ? scene_.models[static_cast<size_t>(m)].name : label.title;
        content.groups[static_cast<size_t>(g)].models.push_back(TreeModelEntry{m, title});
    }
    return content;
}

// In relayout(): the tree in place of the group toggles when they do not all fit.
void KioskApp::add_tree() {
    if (groups_fit()) {
        tree_ = TreeState{};
        return;
    }
    std::erase_if(controls_, [](const Control& c) { return c.id == ControlId::GroupToggle; });
    // Closed, the tree is one button: its content (every model's title) only when open.
    add_tree_controls(ui_state(), tree_.open ? tree_content() : TreeContent{}, tree_, controls_);
}

// `c` lives in controls_, which the actions lay out anew: read it first.
void KioskApp::activate_tree(const Control& c) {
    const ControlId id = c.id;
    const int group = c.group;
    const int page = std::max(1, tree_page_rows(ui_state(), tree_content()) - 1);
    switch (id) {
        case ControlId::TreeOpen: tree_.open = !tree_.open; break;
        case ControlId::TreeSearch: tree_.query.clear(), tree_.first_row = 0; break;
        case ControlId::TreeBackspace:
            if (!tree_.query.empty()) tree_.query.pop_back();
            tree_.first_row = 0;
            break;
        case ControlId::TreeUp: tree_.first_row = std::max(0, tree_.first_row - page); break;
        case ControlId::TreeDown: {
            const int rows = static_cast<int>(tree_rows(tree_content(), tree_).size());
            tree_.first_row = std::min(tree_.first_row + page, std::max(0, rows - 1));
            break;
        }
        case ControlId::TreeLetter:
            tree_.query += static_cast<char32_t>(group);
            tree_.first_row = 0;
            break;
        case ControlId::TreeGroup:
            tree_.opened_group = group;
            set_group_visible(group, !groups_[static_cast<size_t>(group)].visible);
            break;
        case ControlId::TreeModel: {
            const int g = group_index(group);
            if (g >= 0 && !groups_[static_cast<size_t>(g)].visible) set_group_visible(g, true);
            select(group);
            break;
        }
        default: break;
    }
}

// A keyboard's letters search the tree (opening it); backspace and Escape as
// its keys. Returns whether the event was the tree's.
bool KioskApp::tree_key(const InputEvent& e) {
    if (!e.pressed || operator_.active() || groups_fit()) return false;
    if (e.type == InputEvent::Type::Text) {
        const char32_t c = fold_letter(static_cast<char32_t>(e.key));
        if (c <= U' ' || c == 0x7F) return false;
        tree_.open = true;
        tree_.query += c;
        tree_.first_row = 0;
    } else if (e.type == InputEvent::Type::Key && e.key == platform::kKeyBackspace && tree_.open) {
        if (!tree_.query.empty()) tree_.query.pop_back();
        tree_.first_row = 0;
    } else if (e.type == InputEvent::Type::Key && e.key == platform::kKeyEscape && tree_.open) {
        tree_ = TreeState{};
    } else {
        return false;
    }
    relayout();
    return true;
}

}  // namespace body::kiosk
