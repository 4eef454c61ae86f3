// The UTF-8 text entry (contract in text_field.h).
#include "kiosk/author/text_field.h"

#include <algorithm>

namespace body::kiosk::author {

namespace {

bool continuation(unsigned char c) { return (c & 0xC0) == 0x80; }

}  // namespace

void append_utf8(std::string& out, char32_t c) {
    if (c < 0x80) {
        out += static_cast<char>(c);
    } else if (c < 0x800) {
        out += static_cast<char>(0xC0 | (c >> 6));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
        if (c >= 0xD800 && c < 0xE000) return;
        out += static_cast<char>(0xE0 | (c >> 12));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c <= 0x10FFFF) {
        out += static_cast<char>(0xF0 | (c >> 18));
        out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (c & 0x3F));
    }
}

size_t TextField::prev(size_t at) const {
    if (at == 0) return 0;
    --at;
    while (at > 0 && continuation(static_cast<unsigned char>(text_[at]))) --at;
    return at;
}

size_t TextField::next(size_t at) const {
    if (at >= text_.size()) return text_.size();
    ++at;
    while (at < text_.size() && continuation(static_cast<unsigned char>(text_[at]))) ++at;
    return at;
}

void TextField::erase_selection() {
    const size_t b = selection_begin(), e = selection_end();
    text_.erase(b, e - b);
    cursor_ = anchor_ = b;
}

void TextField::insert(char32_t codepoint) {
    if (codepoint < 0x20 || codepoint == 0x7F) return;
    std::string utf8;
    append_utf8(utf8, codepoint);
    if (utf8.empty()) return;
    erase_selection();
    text_.insert(cursor_, utf8);
    cursor_ = anchor_ = cursor_ + utf8.size();
}

void TextField::insert(const std::string& utf8) {
    for (size_t i = 0; i < utf8.size();) {
        const auto c = static_cast<unsigned char>(utf8[i]);
        const size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
        char32_t cp = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
        for (size_t k = 1; k < n && i + k < utf8.size(); ++k)
            cp = (cp << 6) | (static_cast<unsigned char>(utf8[i + k]) & 0x3F);
        insert(cp);
        i += n;
    }
}

void TextField::backspace() {
    if (cursor_ == anchor_) anchor_ = prev(cursor_);
    erase_selection();
}

void TextField::erase_forward() {
    if (cursor_ == anchor_) anchor_ = next(cursor_);
    erase_selection();
}

void TextField::left(bool extend) {
    if (!extend && cursor_ != anchor_) {
        cursor_ = anchor_ = selection_begin();
        return;
    }
    cursor_ = prev(cursor_);
    if (!extend) anchor_ = cursor_;
}

void TextField::right(bool extend) {
    if (!extend && cursor_ != anchor_) {
        cursor_ = anchor_ = selection_end();
        return;
    }
    cursor_ = next(cursor_);
    if (!extend) anchor_ = cursor_;
}

void TextField::home(bool extend) { set_cursor(0, extend); }
void TextField::end(bool extend) { set_cursor(text_.size(), extend); }

void TextField::select_all() {
    anchor_ = 0;
    cursor_ = text_.size();
}

void TextField::set_cursor(size_t at, bool extend) {
    at = std::min(at, text_.size());
    while (at > 0 && at < text_.size() && continuation(static_cast<unsigned char>(text_[at]))) --at;
    cursor_ = at;
    if (!extend) anchor_ = at;
}

}  // namespace body::kiosk::author
