#pragma once
// The kiosk's one table of UI words: every word a control shows, keyed by word
// and language (kUiLanguages; ui_words.cpp holds the table). A word missing in
// a language falls back to English.
#include <span>
#include <string>
#include <string_view>

namespace body::kiosk {

// The languages the table has a column for, in its column order.
inline constexpr std::string_view kUiLanguages[] = {"en", "de", "fr", "es", "ru", "el", "ar", "he", "zh", "ja"};

// The word `key` in `language` (UTF-8): English where the table has none in
// that language; `key` itself for a key the table does not have.
std::string ui_word(std::string_view key, std::string_view language);
// Whether the table has `key`.
bool has_ui_word(std::string_view key);

}  // namespace body::kiosk
