// Structure names -> readable titles and sides (see names.h for the forms).
#include "builder/exhibit/names.h"

#include <cctype>

namespace body::exhibit {
namespace {

bool iequals_prefix(const std::string& s, const std::string& prefix) {
    if (s.size() < prefix.size()) return false;
    for (size_t i = 0; i < prefix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i])))
            return false;
    return true;
}

bool iequals_suffix(const std::string& s, const std::string& suffix) {
    if (s.size() < suffix.size()) return false;
    return iequals_prefix(s.substr(s.size() - suffix.size()), suffix);
}

// Strips one side marker; returns "left", "right" or "".
std::string take_side(std::string& s) {
    static const char* const kPrefixes[][2] = {
        {"ctx-lh-", "left"}, {"ctx-rh-", "right"}, {"lh.", "left"},     {"rh.", "right"},  {"Left-", "left"},
        {"Right-", "right"}, {"Left_", "left"},    {"Right_", "right"}, {"Left ", "left"}, {"Right ", "right"}};
    for (const auto& [prefix, side] : kPrefixes) {
        const std::string p = prefix;
        if (s.size() > p.size() && iequals_prefix(s, p)) {
            s = s.substr(p.size());
            return side;
        }
    }
    static const char* const kSuffixes[][2] = {{"_left", "left"},   {"_right", "right"}, {" left", "left"},
                                               {" right", "right"}, {"_L", "left"},      {"_R", "right"},
                                               {".L", "left"},      {".R", "right"},     {"-L", "left"},
                                               {"-R", "right"},     {" L", "left"},      {" R", "right"}};
    for (const auto& [suffix, side] : kSuffixes) {
        const std::string x = suffix;
        // Single-letter markers are case-sensitive ("_l" may be part of a word).
        const bool match = x.size() == 2 ? s.ends_with(x) : iequals_suffix(s, x);
        if (s.size() > x.size() && match) {
            s.resize(s.size() - x.size());
            return side;
        }
    }
    return {};
}

}  // namespace

ReadableName readable_name(const std::string& name) {
    ReadableName out;
    std::string s = name;
    out.side = take_side(s);
    const bool hyphens_are_spaces = s.find(' ') == std::string::npos && s.find('_') == std::string::npos;
    std::string t;
    for (char c : s) {
        if (c == '_' || (c == '-' && hyphens_are_spaces)) c = ' ';
        if (c == ' ' && (t.empty() || t.back() == ' ')) continue;
        t.push_back(c);
    }
    while (!t.empty() && t.back() == ' ') t.pop_back();
    // Lower-case words that are capitalised only (Frontal Sup -> Frontal sup) but keep acronyms.
    bool word_start = true;
    for (size_t i = 0; i < t.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(t[i]);
        if (word_start && i > 0 && std::isupper(c)) {
            const bool acronym = i + 1 < t.size() && std::isupper(static_cast<unsigned char>(t[i + 1]));
            if (!acronym) t[i] = static_cast<char>(std::tolower(c));
        }
        word_start = c == ' ' || c == '(';
    }
    if (!t.empty()) t[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(t[0])));
    out.title = t.empty() ? name : t;
    return out;
}

}  // namespace body::exhibit
