#pragma once
// Input files before they are opened: only regular files are read (a FIFO
// would block the reader, a device never ends), and text taken from a file is
// escaped before it is echoed in a message; the words of a text line.
#include <cctype>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "shared/error.h"

namespace body {

// ok when `path` (symlinks followed) is a regular file. Otherwise an input
// error naming the path and what it is: "no such file", "is a directory",
// "is a FIFO", "is a device", "is a socket", or the stat error. Does not open
// the file, so it never blocks.
Status check_regular_file(const std::string& path);

// Size in bytes of a regular file (after check_regular_file).
Result<uint64_t> regular_file_size(const std::string& path);

// Refuses an output that would destroy an input: `output` naming the same
// file as one of `inputs` (same path after resolving links, or same inode
// through a hard link), or a directory output that contains an input (it
// is replaced whole). "OUT: is the input INPUT; not overwriting it".
// An existing output that is not a regular file or a directory (a FIFO, a
// device, a socket) is refused too: a write would block or the rename that
// makes it atomic would replace the node. "OUT: is a FIFO; not writing there".
Status check_output_apart(const std::string& output, std::initializer_list<std::string> inputs);
Status check_output_apart(const std::string& output, std::span<const std::string> inputs);

// `text` with control characters, DEL and bytes >= 0x80 written as \xHH (and
// '\\' as "\\\\"), cut to `max` characters with "..." after: safe to print.
std::string escape_for_message(std::string_view text, size_t max = 80);

// `text` with control characters and DEL written as \xHH, everything else (UTF-8
// names included) kept: a message built from file contents stays one line.
std::string escape_control_characters(std::string_view text);

// The whitespace-separated words of `line` into `out` (cleared first), as
// views into `line`: the text mesh formats' (OBJ, PLY) value rows. Whitespace is
// the C locale's (what std::isspace means here; inline: a call per byte was a
// tenth of checking a large OBJ).
inline void split_words(std::string_view line, std::vector<std::string_view>& out) {
    auto space = [](char c) { return c == ' ' || (c >= '\t' && c <= '\r'); };
    out.clear();
    for (size_t i = 0; i < line.size();) {
        while (i < line.size() && space(line[i])) ++i;
        size_t j = i;
        while (j < line.size() && !space(line[j])) ++j;
        if (j > i) out.push_back(line.substr(i, j - i));
        i = j;
    }
}

}  // namespace body
