#pragma once
// Writes that never leave a half-written file: data goes to "<path>.tmp-<pid>"
// in the same directory, is flushed, then renamed over <path>. On failure the
// temporary file is removed and <path> is untouched. Directories are staged the
// same way ("<dir>.tmp-<pid>") and swapped into place by renames.
// Temporaries of this process (staged directories whole) are removed on SIGINT/SIGTERM/SIGHUP once
// remove_temporaries_on_signal() ran; those a killed process left behind
// (its pid no longer alive) are swept by the next write to the same path.
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

// Builds a directory: `fill(staged)` writes into the empty directory `staged`,
// which then replaces `dir` (an existing `dir` is moved aside and removed last).
// `replaceable(dir)` says whether an existing `dir` may be replaced; when it
// returns a reason, nothing is written and the error names `dir`.
Status write_directory_atomically(const std::string& dir, const std::function<Status(const std::string&)>& fill,
                                  const std::function<std::string(const std::string&)>& replaceable);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that unlink this process's
// temporary files, then end the process as the signal would.
void remove_temporaries_on_signal();

// Removes "<path>.tmp-<pid>" files and directories whose process is gone.
void sweep_stale_temporaries(const std::string& path);

// A scratch file or directory of this process, "<path>.tmp-<pid>": stale ones
// of `path` are swept first; it is removed (whole, if a directory) when this
// goes out of scope or on SIGINT/SIGTERM/SIGHUP, and by the next sweep after
// a SIGKILL. Nothing is created: the caller makes path().
class ScratchPath {
public:
    explicit ScratchPath(const std::string& path);
    ~ScratchPath();
    ScratchPath(const ScratchPath&) = delete;
    ScratchPath& operator=(const ScratchPath&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
    int slot_ = -1;
};

// `message` with every `from` (a temporary path, gone by the time it is read)
// written as `to` (the output it stood for).
std::string renamed_in_message(std::string message, const std::string& from, const std::string& to);

// Reads a whole file; error names the path and the reason.
Result<std::string> read_file(const std::string& path);

}  // namespace body
