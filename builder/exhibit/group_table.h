#pragma once
// Group pattern tables: which exhibit group a structure joins, by its name.
//
// Text, one rule per line: `PATTERN<TAB>GROUP`; `#` comments, blank lines and a
// header line `pattern<TAB>group` are skipped. PATTERN is a shell glob
// (fnmatch(3): * ? [...]) matched against the structure's name as the source
// spells it; rules are tried in order and the first match wins; unmatched
// structures join `fallback`. In GROUP, `{side}` becomes the structure's side
// (left/right, names.h) or nothing, with the separators around it dropped:
// `frontal-{side}` gives frontal-left, frontal-right or frontal.
// Example: builder/import/aal_groups.tsv (the AAL atlas by lobe and side).
#include <string>
#include <vector>

#include "shared/error.h"

namespace body::exhibit {

struct GroupRule {
    std::string pattern;
    std::string group;
};

struct GroupTable {
    std::vector<GroupRule> rules;
    std::string fallback = "other";
    // The group of `name` (whose side is `side`, possibly empty).
    std::string group_of(const std::string& name, const std::string& side) const;
};

// Errors: "PATH:LINE: reason" (exit 2).
Result<GroupTable> parse_group_table(const std::string& text, const std::string& path);
Result<GroupTable> read_group_table(const std::string& path);

}  // namespace body::exhibit
