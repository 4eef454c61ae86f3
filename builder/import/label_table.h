#pragma once
// Label tables: which label value is which structure, and its colour.
//
// Accepted forms (detected per file / per line):
// - text, one label per line, `#` comments and blank lines ignored, CRLF ok:
//     `index name`                       (plain; JHU/MRIcron .txt, tab or space separated)
//     `index name code`                  (MRIcron/AAL .txt: a trailing number that is not a colour is ignored)
//     `index name r g b [a]`             (FreeSurfer-style LUT: 0-255 integers)
//     `index r g b name...`              (FSL/FSLeyes .lut: r g b floats in [0, 1])
//     `index r g b a vis mesh "name"`    (ITK-SNAP label description: 0-255, a line with a quote)
//   Names may contain spaces in the first and last forms.
// - binary MRIcron .lut: exactly 768 bytes, 256 red, then 256 green, then 256
//   blue bytes, indexed by label value: colours only.
// Label 0 is the background and is never a structure; a table may still list it.
// Errors name the path, the line and the reason (duplicate index, missing
// name, negative or non-numeric index, bad colour).
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

struct LabelEntry {
    std::string name;           // empty when the table only gives a colour
    std::optional<Vec3> color;  // RGB in [0, 1]
};

struct LabelTable {
    std::map<int64_t, LabelEntry> entries;
};

Result<LabelTable> parse_label_table(const std::string& text, const std::string& path);
// Reads a text table or a binary MRIcron .lut.
Result<LabelTable> read_label_table(const std::string& path);
// `base` gains entries of `extra` where missing, and colours it lacks.
void merge_label_table(LabelTable& base, const LabelTable& extra);

}  // namespace body
