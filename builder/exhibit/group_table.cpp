// Group pattern tables (format in group_table.h).
#include "builder/exhibit/group_table.h"

#include <fnmatch.h>

#include "shared/atomic_file.h"
#include "shared/text_lines.h"

namespace body::exhibit {

std::string GroupTable::group_of(const std::string& name, const std::string& side) const {
    for (const GroupRule& r : rules) {
        if (::fnmatch(r.pattern.c_str(), name.c_str(), 0) != 0) continue;
        std::string g = r.group;
        const size_t at = g.find("{side}");
        if (at == std::string::npos) return g;
        g.replace(at, 6, side);
        if (side.empty()) {
            // Drop the separator the placeholder leaves behind ("frontal-" / "-frontal" / "a--b").
            const auto sep = [](char c) { return c == '-' || c == '_' || c == ' '; };
            if (at > 0 && at < g.size() && sep(g[at - 1]) && sep(g[at]))
                g.erase(at, 1);
            else if (at > 0 && at == g.size() && sep(g[at - 1]))
                g.erase(at - 1, 1);
            else if (at == 0 && !g.empty() && sep(g[0]))
                g.erase(0, 1);
        }
        return g.empty() ? fallback : g;
    }
    return fallback;
}

Result<GroupTable> parse_group_table(const std::string& text, const std::string& path) {
    GroupTable table;
    Status walked = for_each_text_line(text, path, [&](const std::string& line, const std::string& where) -> Status {
        if (line.empty() || line[0] == '#' || line == "pattern\tgroup") return ok_status();
        const size_t tab = line.find('\t');
        if (tab == std::string::npos || line.find('\t', tab + 1) != std::string::npos)
            return input_error(where + "expected 'PATTERN<TAB>GROUP'");
        GroupRule r{line.substr(0, tab), line.substr(tab + 1)};
        if (r.pattern.empty() || r.group.empty()) return input_error(where + "empty pattern or group");
        table.rules.push_back(std::move(r));
        return ok_status();
    });
    if (!walked) return walked.error();
    if (table.rules.empty()) return input_error(path + ": no rules in the group table");
    return table;
}

Result<GroupTable> read_group_table(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_group_table(*text, path);
}

}  // namespace body::exhibit
