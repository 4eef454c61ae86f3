#pragma once
// A one-line UTF-8 text entry: the text, a cursor and a selection (both byte
// offsets, always on codepoint boundaries). Typing replaces the selection;
// Shift with the arrows, Home and End extends it. No GL: the panel draws it.
#include <string>

namespace body::kiosk::author {

class TextField {
public:
    TextField() = default;
    explicit TextField(std::string text) : text_(std::move(text)), cursor_(text_.size()), anchor_(0) {}

    const std::string& text() const { return text_; }
    size_t cursor() const { return cursor_; }
    // The selection as [begin, end) byte offsets (empty: begin == end == cursor).
    size_t selection_begin() const { return std::min(cursor_, anchor_); }
    size_t selection_end() const { return std::max(cursor_, anchor_); }
    std::string selected() const { return text_.substr(selection_begin(), selection_end() - selection_begin()); }

    // Inserts a codepoint (invalid ones and control characters are ignored), or UTF-8 text.
    void insert(char32_t codepoint);
    void insert(const std::string& utf8);
    void backspace();
    void erase_forward();  // Delete
    void left(bool extend);
    void right(bool extend);
    void home(bool extend);
    void end(bool extend);
    void select_all();
    // Places the cursor at byte offset `at` (moved back to a codepoint boundary).
    void set_cursor(size_t at, bool extend);

private:
    void erase_selection();
    size_t prev(size_t at) const;
    size_t next(size_t at) const;

    std::string text_;
    size_t cursor_ = 0, anchor_ = 0;
};

// Appends a codepoint as UTF-8 (nothing for surrogates or values past U+10FFFF).
void append_utf8(std::string& out, char32_t codepoint);

}  // namespace body::kiosk::author
