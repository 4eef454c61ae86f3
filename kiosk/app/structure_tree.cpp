// The structure tree's search and layout (the contract is in structure_tree.h).
#include "kiosk/app/structure_tree.h"

#include <algorithm>
#include <cmath>

#include "kiosk/app/text.h"
#include "kiosk/app/text_shaping.h"
#include "kiosk/app/ui_words.h"

namespace body::kiosk {
namespace {

std::string encode_utf8(char32_t c) {
    std::string s;
    if (c < 0x80) {
        s += static_cast<char>(c);
    } else if (c < 0x800) {
        s += static_cast<char>(0xC0 | (c >> 6));
        s += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        s += static_cast<char>(0xE0 | (c >> 12));
        s += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (c & 0x3F));
    } else {
        s += static_cast<char>(0xF0 | (c >> 18));
        s += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        s += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        s += static_cast<char>(0x80 | (c & 0x3F));
    }
    return s;
}

char32_t upper_letter(char32_t c) {
    if ((c >= U'a' && c <= U'z') || (c >= 0xE0 && c <= 0xFE && c != 0xF7) || (c >= 0x3B1 && c <= 0x3C9 && c != 0x3C2) ||
        (c >= 0x430 && c <= 0x44F))
        return c - 0x20;
    return c;
}

bool word_start(const std::u32string& t, size_t i) {
    return i == 0 || t[i - 1] == U' ' || t[i - 1] == U'-' || t[i - 1] == U'_' || t[i - 1] == U'(';
}

// The panel's frame: left edge, top, width and the bottom of the list.
struct Frame {
    float b, key, gap, x, y, w, bottom;
};

// The panel runs from the left edge to the control column's leftmost column
// (column_cell: rows that do not fit flow into columns further left).
Frame panel_frame(const UiState& s) {
    Frame f;
    f.b = button_size(s);
    f.key = min_target_px(s);
    f.gap = std::floor(f.b * 0.15f);
    f.x = f.gap + s.drift_x;
    f.y = f.gap + s.drift_y;
    float column_left = static_cast<float>(s.width);
    const int rows = kColumnRows + (s.access_buttons ? 1 : 0);  // the access toggles' row follows (access.h)
    for (int row = 0; row < rows; ++row) column_left = std::min(column_left, column_cell(s, row).x);
    // Too little room beside every column (large text on a small screen): the
    // panel covers the columns after the first, whose controls it hides while open.
    if (column_left - f.gap - f.x < 4.0f * f.b) column_left = column_cell(s, 0).x;
    f.w = std::max(4.0f * f.b, std::min(8.0f * f.b, column_left - f.gap - f.x));
    f.bottom = static_cast<float>(s.height) - f.b - 2.0f * f.gap + s.drift_y;  // above the group row
    return f;
}

int keys_per_row(const Frame& f) { return std::max(1, static_cast<int>((f.w + f.gap) / (f.key + f.gap))); }

// One or two rows of letters, two only where three list rows stay below them.
int letter_rows(const Frame& f, size_t letters) {
    const int per = keys_per_row(f);
    const int needed = static_cast<int>((letters + static_cast<size_t>(per) - 1) / static_cast<size_t>(per));
    const float room = f.bottom - (f.y + f.b + f.gap) - 3.0f * (f.b + f.gap);
    const int fit = std::max(1, static_cast<int>((room + f.gap) / (f.key + f.gap)));
    return std::min({2, needed, fit});
}

Control control(ControlId id, int group, Rect r, std::string text, bool active = false, bool enabled = true) {
    return Control{id, group, r, std::move(text), enabled, active};
}

}  // namespace

char32_t fold_letter(char32_t c) {
    if ((c >= U'A' && c <= U'Z') || (c >= 0xC0 && c <= 0xDE && c != 0xD7) || (c >= 0x391 && c <= 0x3A9) ||
        (c >= 0x410 && c <= 0x42F))
        return c + 0x20;
    return c;
}

bool title_matches(std::string_view title, const std::u32string& query) {
    if (query.empty()) return true;
    std::u32string t = decode_utf8(title);
    for (char32_t& c : t) c = fold_letter(c);
    for (size_t i = 0; i + query.size() <= t.size(); ++i) {
        if (word_start(t, i) && t.compare(i, query.size(), query) == 0) return true;
    }
    return false;
}

std::vector<TreeRow> tree_rows(const TreeContent& content, const TreeState& state) {
    std::vector<TreeRow> rows;
    for (size_t g = 0; g < content.groups.size(); ++g) {
        const TreeGroupEntry& e = content.groups[g];
        const int gi = static_cast<int>(g);
        const bool group_match = title_matches(e.title, state.query);
        std::vector<TreeRow> below;
        for (const TreeModelEntry& m : e.models) {
            // Searching: the models that match; else the opened group's models.
            const bool show = state.query.empty() ? gi == state.opened_group : title_matches(m.title, state.query);
            if (show) below.push_back(TreeRow{gi, m.model});
        }
        if (!group_match && below.empty()) continue;
        rows.push_back(TreeRow{gi, -1});
        rows.insert(rows.end(), below.begin(), below.end());
    }
    return rows;
}

std::vector<char32_t> tree_letters(const TreeContent& content) {
    std::vector<char32_t> letters;
    const auto add = [&](std::string_view title) {
        std::u32string t = decode_utf8(title);
        for (size_t i = 0; i < t.size(); ++i) {
            const char32_t c = fold_letter(t[i]);
            if (word_start(t, i) && c != U' ' && !(c >= U'0' && c <= U'9')) letters.push_back(c);
        }
    };
    for (const TreeGroupEntry& g : content.groups) {
        add(g.title);
        for (const TreeModelEntry& m : g.models) add(m.title);
    }
    std::sort(letters.begin(), letters.end());
    letters.erase(std::unique(letters.begin(), letters.end()), letters.end());
    return letters;
}

int tree_page_rows(const UiState& ui, const TreeContent& content) {
    const Frame f = panel_frame(ui);
    const float top =
        f.y + f.b + f.gap + static_cast<float>(letter_rows(f, tree_letters(content).size())) * (f.key + f.gap);
    return std::max(1, static_cast<int>((f.bottom - top + f.gap) / (f.b + f.gap)));
}

void add_tree_controls(const UiState& ui, const TreeContent& content, const TreeState& state,
                       std::vector<Control>& out) {
    std::vector<Control> tree;
    const Frame f = panel_frame(ui);
    const float gy = static_cast<float>(ui.height) - f.b - f.gap + ui.drift_y;  // the group row (ui.cpp)
    tree.push_back(control(ControlId::TreeOpen, -1, Rect{f.x, gy, std::floor(f.b * 2.4f), f.b},
                           ui_word("structures", ui.language), state.open));
    if (state.open) {
        // The search line: the letters typed, backspace, page up, page down.
        const std::vector<TreeRow> rows = tree_rows(content, state);
        const int page = tree_page_rows(ui, content);
        const int first = std::clamp(state.first_row, 0, std::max(0, static_cast<int>(rows.size()) - page));
        const float kx = f.x + f.w - 3.0f * f.b - 2.0f * f.gap;
        std::string query;
        for (char32_t c : state.query) query += encode_utf8(upper_letter(c));
        tree.push_back(control(ControlId::TreeSearch, -1, Rect{f.x, f.y, kx - f.gap - f.x, f.b},
                               ui_word("search", ui.language) + ": " + query + "_", !state.query.empty()));
        tree.push_back(
            control(ControlId::TreeBackspace, -1, Rect{kx, f.y, f.b, f.b}, "⌫", false, !state.query.empty()));
        tree.push_back(control(ControlId::TreeUp, -1, Rect{kx + f.b + f.gap, f.y, f.b, f.b}, "▲", false, first > 0));
        tree.push_back(control(ControlId::TreeDown, -1, Rect{kx + 2.0f * (f.b + f.gap), f.y, f.b, f.b}, "▼", false,
                               first + page < static_cast<int>(rows.size())));
        // The letter strip.
        const std::vector<char32_t> letters = tree_letters(content);
        const int per = keys_per_row(f);
        const int shown = std::min<int>(static_cast<int>(letters.size()), letter_rows(f, letters.size()) * per);
        const float ly = f.y + f.b + f.gap;
        for (int i = 0; i < shown; ++i) {
            const Rect r{f.x + static_cast<float>(i % per) * (f.key + f.gap),
                         ly + static_cast<float>(i / per) * (f.key + f.gap), f.key, f.key};
            const char32_t c = letters[static_cast<size_t>(i)];
            tree.push_back(control(ControlId::TreeLetter, static_cast<int>(c), r, encode_utf8(upper_letter(c))));
        }
        // The list.
        const float top = ly + static_cast<float>(letter_rows(f, letters.size())) * (f.key + f.gap);
        for (int k = 0; k < page && first + k < static_cast<int>(rows.size()); ++k) {
            const TreeRow& row = rows[static_cast<size_t>(first + k)];
            const TreeGroupEntry& g = content.groups[static_cast<size_t>(row.group)];
            const Rect r{f.x, top + static_cast<float>(k) * (f.b + f.gap), f.w, f.b};
            if (row.model < 0) {
                const bool opened = row.group == state.opened_group || !state.query.empty();
                tree.push_back(control(ControlId::TreeGroup, row.group, r, std::string(opened ? "▾ " : "▸ ") + g.title,
                                       g.visible));
                continue;
            }
            std::string title;
            for (const TreeModelEntry& m : g.models)
                if (m.model == row.model) title = m.title;
            const float indent = std::floor(f.b * 0.5f);
            tree.push_back(control(ControlId::TreeModel, row.model, Rect{r.x + indent, r.y, r.w - indent, r.h}, title,
                                   row.model == content.selected_model));
        }
    }
    if (state.open) {  // the controls under the panel give way while it is open
        Rect panel{f.x, f.y, f.w, f.bottom - f.y};
        if (is_rtl_language(ui.language)) panel.x = static_cast<float>(ui.width) - panel.x - panel.w;
        std::erase_if(out, [&](const Control& c) {
            return c.rect.x < panel.x + panel.w && panel.x < c.rect.x + c.rect.w && c.rect.y < panel.y + panel.h &&
                   panel.y < c.rect.y + c.rect.h;
        });
    }
    if (is_rtl_language(ui.language)) mirror_for_rtl(tree, ui.width);
    out.insert(out.end(), tree.begin(), tree.end());
}

}  // namespace body::kiosk
