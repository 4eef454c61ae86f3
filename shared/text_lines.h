#pragma once
// The one line walk of the text tables bodygen reads (label tables, group
// patterns, translations): lines split at '\n', a trailing '\r' removed,
// numbered from 1 for the located error `PATH:LINE: reason`.
#include <cstddef>
#include <string>
#include <string_view>

#include "shared/error.h"

namespace body {

// Calls `fn(std::string& line, const std::string& where)` for every line of `text`;
// `where` is "PATH:LINE: ". The first failing Status stops the walk and is returned.
template <class Fn>
Status for_each_text_line(const std::string& text, const std::string& path, Fn&& fn) {
    size_t pos = 0, line_no = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(pos, end - pos);
        pos = end + 1;
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        Status s = fn(line, path + ":" + std::to_string(line_no) + ": ");
        if (!s) return s;
    }
    return ok_status();
}

}  // namespace body
