#pragma once
// bodygen subcommands. Each takes the arguments after the subcommand name and
// returns a process exit code (0 ok, 1 runtime failure, 2 bad usage/input).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/scene/scene_pack.h"

namespace body::cli {

using Args = std::vector<std::string>;

struct Command {
    const char* name;
    const char* summary;
    int (*run)(const Args& args);
};

// Prints "bodygen: <message>" on stderr and returns the error's exit code.
int report(const Error& error);

// A progress bar on stderr, `[####    ] DONE/TOTAL UNIT`, erased when done reaches
// total; for the `progress` callbacks of the long commands (callers check isatty).
std::function<void(size_t, size_t)> progress_bar(const char* unit);

// `bodygen pack` without the printing: shared/scene/scene_pack.h.
using scene::pack_scene;
using scene::PackSummary;

}  // namespace body::cli
