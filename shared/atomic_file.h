#pragma once
// Writes that never leave a half-written file: data goes to "<path>.tmp-<pid>"
// in the same directory, is flushed, then renamed over <path>. On failure the
// temporary file is removed and <path> is untouched.
#include <functional>
#include <ostream>
#include <span>
#include <string>

#include "shared/error.h"

namespace body {

// Calls `write(stream)`; the callback returns an empty string on success or a
// reason. Returns an error naming `path` on any failure.
Status write_file_atomically(const std::string& path, const std::function<std::string(std::ostream&)>& write);
Status write_file_atomically(const std::string& path, std::span<const uint8_t> bytes);

// Reads a whole file; error names the path and the reason.
Result<std::string> read_file(const std::string& path);

}  // namespace body
