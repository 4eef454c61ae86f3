// Translation tables (format in translations.h).
#include "builder/exhibit/translations.h"

#include <algorithm>

#include "shared/atomic_file.h"
#include "shared/text_lines.h"

namespace body::exhibit {

Result<Translations> parse_translations(const std::string& text, const std::string& path) {
    Translations t;
    Status walked = for_each_text_line(text, path, [&](const std::string& line, const std::string& where) -> Status {
        if (line.empty() || line[0] == '#' || line.starts_with("name\t")) return ok_status();
        std::vector<std::string> cells;
        size_t a = 0;
        for (size_t b; (b = line.find('\t', a)) != std::string::npos; a = b + 1) cells.push_back(line.substr(a, b - a));
        cells.push_back(line.substr(a));
        if (cells.size() == 3) cells.emplace_back();
        if (cells.size() != 4) return input_error(where + "expected 'NAME<TAB>LANG<TAB>TITLE<TAB>DESCRIPTION'");
        if (cells[0].empty() || cells[1].empty() || cells[2].empty())
            return input_error(where + "empty name, language or title");
        for (char c : cells[1])
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_')
                return input_error(where + "language '" + cells[1] + "' is not a language code");
        auto& langs = t.rows[cells[0]];
        if (!langs.emplace(cells[1], Translation{cells[2], cells[3]}).second)
            return input_error(where + "a second row for '" + cells[0] + "' in '" + cells[1] + "'");
        if (std::find(t.languages.begin(), t.languages.end(), cells[1]) == t.languages.end())
            t.languages.push_back(cells[1]);
        return ok_status();
    });
    if (!walked) return walked.error();
    if (t.rows.empty()) return input_error(path + ": no translations in the table");
    return t;
}

Result<Translations> read_translations(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_translations(*text, path);
}

}  // namespace body::exhibit
