#pragma once
// Label translations for exhibits: a UTF-8 TSV, one row per structure and language:
//   NAME<TAB>LANG<TAB>TITLE<TAB>DESCRIPTION
// NAME is the structure's name as the source spells it (or its model name);
// LANG a language code ("de", "fr", "en"...). `#` comments, blank lines and a header
// line starting `name<TAB>` are skipped; DESCRIPTION may be empty. A row for
// "en" replaces the readable title made from the name.
#include <map>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body::exhibit {

struct Translation {
    std::string title, description;
};

struct Translations {
    // name -> language -> text
    std::map<std::string, std::map<std::string, Translation>> rows;
    std::vector<std::string> languages;  // in order of first appearance
};

// Errors: "PATH:LINE: reason" (exit 2), e.g. a duplicate (name, language).
Result<Translations> parse_translations(const std::string& text, const std::string& path);
Result<Translations> read_translations(const std::string& path);

}  // namespace body::exhibit
