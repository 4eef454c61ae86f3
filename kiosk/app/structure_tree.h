#pragma once
// The structure tree: when the scene's groups do not fit the bottom row as one
// toggle each, the row holds one button instead (TreeOpen) that opens a panel
// on the left (on the right for a right-to-left language): a search line with
// backspace and page keys, a strip of letter keys, and the list of groups with
// the opened group's models below it.
//
// Type-ahead: a letter key, or a letter typed on a keyboard, narrows the list
// to the groups and models with a word that starts with the letters typed
// (case folded for Latin, Greek and Cyrillic); a group is listed when its name
// or one of its models matches, the matching models below it. A tap on a group
// shows or hides it (as its toggle does) and opens it; a tap on a model selects it.
//
// No GL: controls (ui.h) the overlay draws like the others, finger-sized
// (the letter keys min_target_px square, the rows button_size tall), beside
// the control column (where that leaves under four buttons' width, over the
// column's later columns, whose controls give way while it is open). Letters beyond the strip's rows (two, or one where
// two would leave fewer than three list rows) are left off it; a keyboard still types them.
#include <string>
#include <string_view>
#include <vector>

#include "kiosk/app/ui.h"

namespace body::kiosk {

// What the tree lists: per group its title, whether it is shown, its models.
struct TreeModelEntry {
    int model = -1;
    std::string title;
};
struct TreeGroupEntry {
    std::string title;
    bool visible = true;
    std::vector<TreeModelEntry> models;
};
struct TreeContent {
    std::vector<TreeGroupEntry> groups;
    int selected_model = -1;
};

// What the visitor has done with the panel.
struct TreeState {
    bool open = false;
    std::u32string query;  // letters typed, case folded
    int opened_group = -1;
    int first_row = 0;  // the list's first row on screen (clamped by the layout)
};

// One row of the list.
struct TreeRow {
    int group = -1;
    int model = -1;  // -1: the group's own row
};

// Case folding for the search (ASCII, Latin-1, Greek, Cyrillic; others unchanged).
char32_t fold_letter(char32_t c);
// Whether some word of `title` (after a space, hyphen or the start) starts with `query`.
bool title_matches(std::string_view title, const std::u32string& query);
// The rows listed for `content` and `state`, top to bottom.
std::vector<TreeRow> tree_rows(const TreeContent& content, const TreeState& state);
// The distinct first letters of the titles' words, folded, in code point order.
std::vector<char32_t> tree_letters(const TreeContent& content);
// How many list rows the panel shows at once for `ui` and `content`.
int tree_page_rows(const UiState& ui, const TreeContent& content);
// Appends the tree's button (in the group row's place) and, when open, the panel.
void add_tree_controls(const UiState& ui, const TreeContent& content, const TreeState& state,
                       std::vector<Control>& out);

}  // namespace body::kiosk
